/*
 * The C ABI from C: the full cycle on a bundled mesh and every documented misuse.
 * Usage: test_capi SOURCE_DIR. Exits non-zero (printing each failed check) on failure.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "progsim.h"

static char source_dir[4096];

static const char* path_in_source(const char* relative) {
  static char path[8192];
  snprintf(path, sizeof path, "%s/%s", source_dir, relative);
  return path;
}

/* A 2 × 2 grid of unit squares (9 vertices, 8 faces) in the x-y plane. */
static const double kGridVertices[27] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1,
                                         0, 2, 1, 0, 0, 2, 0, 1, 2, 0, 2, 2, 0};
static const int32_t kGridFaces[24] = {0, 1, 4, 0, 4, 3, 1, 2, 4, 2, 5, 4,
                                       3, 4, 6, 4, 7, 6, 4, 5, 8, 4, 8, 7};

static void test_version(void) {
  CHECK(ps_version() == PS_VERSION_HEADER);
  CHECK(ps_check_version(PS_VERSION_HEADER) == PS_OK);
  CHECK_ERROR(ps_check_version(PS_VERSION_HEADER + 10000), PS_ERROR_VERSION_MISMATCH,
              ps_last_error(), "rebuild the caller");
  /* Before 1.0 an older minor's structs are smaller than the library's: refused. */
  CHECK_ERROR(ps_check_version(PS_VERSION_HEADER - 100), PS_ERROR_VERSION_MISMATCH, ps_last_error(),
              "rebuild the caller");
  CHECK(strcmp(ps_status_name(PS_ERROR_INVALID_MESH), "PS_ERROR_INVALID_MESH") == 0);
}

static void test_threads(void) {
  int32_t setting = -1, current = -1;
  CHECK(ps_set_threads(2) == PS_OK);
  CHECK(ps_get_threads(&setting, &current) == PS_OK && setting == 2 && current == 2);
  CHECK_ERROR(ps_set_threads(-1), PS_ERROR_INVALID_ARGUMENT, ps_last_error(), "thread count -1");
  CHECK_ERROR(ps_set_threads(1025), PS_ERROR_INVALID_ARGUMENT, ps_last_error(), "1 to 1024");
  CHECK(ps_get_threads(&setting, NULL) == PS_OK && setting == 2); /* unchanged */
  CHECK(ps_set_threads(0) == PS_OK);
  CHECK(ps_get_threads(&setting, &current) == PS_OK && setting == 0 && current >= 1);
  CHECK(ps_get_threads(NULL, NULL) == PS_OK);
}

static int32_t cancel_after_two(void* user_data, int32_t done, int32_t total, const char* phase) {
  int* calls = (int*)user_data;
  ++*calls;
  (void)total;
  CHECK(strcmp(phase, "preview") == 0);
  return done >= 2;
}

/* A callback that calls back into the running simulation: refused, not crashed. */
static int32_t call_back_in(void* user_data, int32_t done, int32_t total, const char* phase) {
  ps_sim* sim = (ps_sim*)user_data;
  (void)done;
  (void)total;
  (void)phase;
  CHECK_ERROR(ps_sim_step_preview(sim, 1), PS_ERROR_WRONG_CALL_ORDER, ps_sim_last_error(sim),
              "progress callback");
  return 0;
}

static void test_full_cycle(void) {
  ps_hierarchy* h = NULL;
  CHECK(ps_hierarchy_create_from_file(NULL, path_in_source("scenes/meshes/square_cloth.obj"), &h) ==
        PS_OK);
  if (!h) return;
  int32_t levels = 0;
  size_t nv = 0, nf = 0, count = 0;
  CHECK(ps_hierarchy_num_levels(h, &levels) == PS_OK && levels == 1);
  CHECK(ps_hierarchy_level_size(h, 0, &nv, &nf) == PS_OK && nv == 441 && nf == 800);

  ps_sim_def def;
  ps_sim_def_init(&def);
  const int32_t corners[2] = {420, 440}; /* (0, 1, 0) and (1, 1, 0) */
  def.pinned_vertices = corners;
  def.num_pinned_vertices = 2;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  if (!sim) return;
  CHECK(ps_sim_set_param(sim, "material.thickness", 5e-4) == PS_OK);
  double value = 0;
  CHECK(ps_sim_get_param(sim, "material.thickness", &value) == PS_OK && value == 5e-4);
  CHECK(ps_sim_set_param(sim, "gravity.y", 0.0) == PS_OK); /* fall out of the cloth's plane */
  CHECK(ps_sim_set_param(sim, "gravity.z", -9.0) == PS_OK);
  CHECK(ps_sim_get_param(sim, "gravity.z", &value) == PS_OK && value == -9.0);
  CHECK(ps_sim_set_effect(sim, PS_EFFECT_BENDING, 0) == PS_OK);
  uint32_t effects = 0;
  CHECK(ps_sim_get_effects(sim, &effects) == PS_OK &&
        effects == (PS_EFFECT_MEMBRANE | PS_EFFECT_GRAVITY));

  CHECK(ps_sim_step_preview(sim, 10) == PS_OK);
  CHECK(ps_sim_get_positions(sim, 0, NULL, 0, &count) == PS_OK && count == 3 * 441);
  double* x = malloc(count * sizeof(double));
  CHECK(ps_sim_get_positions(sim, 0, x, count, &count) == PS_OK);
  double lowest = INFINITY;
  for (size_t i = 0; i < 441; ++i) lowest = fmin(lowest, x[3 * i + 2]);
  CHECK(lowest < -0.03); /* started flat at z = 0; free fall gives 0.045 m in 0.1 s */
  CHECK(x[3 * 420 + 2] == 0.0 && x[3 * 440 + 2] == 0.0); /* pinned corners held */
  free(x);

  ps_level_stats stats;
  CHECK(ps_sim_get_level_stats(sim, 0, &stats) == PS_OK);
  CHECK(stats.steps == 10 && stats.newton_iterations >= 10 && stats.seconds > 0);
  CHECK(isfinite(stats.energy) && isnan(stats.error_rms));

  int calls = 0;
  CHECK(ps_sim_set_progress_callback(sim, cancel_after_two, &calls) == PS_OK);
  CHECK_ERROR(ps_sim_step_preview(sim, 10), PS_ERROR_CANCELLED, ps_sim_last_error(sim),
              "after 2 of 10");
  CHECK(calls == 2);
  CHECK(ps_sim_get_level_stats(sim, 0, &stats) == PS_OK && stats.steps == 12);

  CHECK(ps_sim_set_progress_callback(sim, call_back_in, sim) == PS_OK);
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  CHECK_ERROR(ps_sim_refine(sim), PS_ERROR_OUT_OF_RANGE, ps_sim_last_error(sim), "finest level 0");
  CHECK_ERROR(ps_sim_refine_window(sim, 0, 1), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "progressive animation");
  CHECK_ERROR(ps_sim_refine_window(NULL, 0, 1), PS_ERROR_NULL_ARGUMENT, ps_last_error(),
              "sim is NULL");
  const double offset[3] = {0.1, 0, 0};
  CHECK(ps_sim_set_handle_motion(sim, 0, NULL, NULL, NULL, 0.0, offset) == PS_OK);
  CHECK(ps_sim_set_progress_callback(sim, NULL, NULL) == PS_OK);
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  double corner[3 * 441];
  CHECK(ps_sim_get_positions(sim, 0, corner, 3 * 441, &count) == PS_OK);
  CHECK(fabs(corner[3 * 420] - 0.1) < 1e-12); /* the dragged handle moved */
  ps_sim_destroy(sim);
  ps_hierarchy_destroy(h);
}

/* A square cloth hanging in its plane from its top edge (y = 1): its support carries the
 * weight ρ h A g = 200 kg/m³ × 1 mm × 1 m² × 9.81 m/s². */
static void test_handle_reaction(void) {
  ps_hierarchy* h = NULL;
  CHECK(ps_hierarchy_create_from_file(NULL, path_in_source("scenes/meshes/square_cloth.obj"), &h) ==
        PS_OK);
  if (!h) return;
  ps_sim_def def;
  ps_sim_def_init(&def);
  int32_t top[21];
  for (int32_t i = 0; i < 21; ++i) top[i] = 420 + i;
  def.pinned_vertices = top;
  def.num_pinned_vertices = 21;
  def.mode = PS_MODE_QUASISTATIC;
  def.solver_newton_tolerance = 1e-9;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  if (!sim) return;
  ps_handle_reaction r;
  CHECK_ERROR(ps_sim_get_handle_reaction(sim, 0, 0, &r), PS_ERROR_WRONG_CALL_ORDER,
              ps_sim_last_error(sim), "no reaction");
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  CHECK(ps_sim_get_handle_reaction(sim, 0, 0, &r) == PS_OK);
  const double weight = 200.0 * 1e-3 * 1.0 * 9.81;
  CHECK(fabs(r.force[1] - weight) < 1e-6 * weight);
  CHECK(fabs(r.force[0]) < 1e-6 * weight && fabs(r.force[2]) < 1e-6 * weight);
  CHECK(fabs(r.point[1] - 1.0) < 1e-3 && fabs(r.point[0] - 0.5) < 1e-9);
  CHECK_ERROR(ps_sim_get_handle_reaction(sim, 0, 1, &r), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim), "handle 1");
  CHECK_ERROR(ps_sim_get_handle_reaction(sim, 2, 0, &r), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim), "level 2");
  CHECK_ERROR(ps_sim_get_handle_reaction(sim, 0, 0, NULL), PS_ERROR_NULL_ARGUMENT,
              ps_sim_last_error(sim), "out");
  CHECK_ERROR(ps_sim_set_handle_axes(sim, 0, 0), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "axes");
  CHECK_ERROR(ps_sim_set_handle_axes(sim, 0, 8), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "axes");
  CHECK_ERROR(ps_sim_set_handle_axes(sim, 3, PS_AXIS_Y), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim), "handle 3");
  CHECK(ps_sim_set_handle_axes(sim, 0, PS_AXIS_ALL) == PS_OK);
  /* A rotation support holding the top edge's height and orientation, free in x and z: the
   * cloth hangs as before (it is symmetric), the support still carries the weight in y and
   * nothing along its free translation. */
  CHECK_ERROR(ps_sim_set_handle_support(sim, 0, 7, PS_AXIS_Y), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "ps_support");
  CHECK_ERROR(ps_sim_set_handle_support(sim, 0, PS_SUPPORT_POSITION, 0), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "axes");
  CHECK(ps_sim_set_handle_support(sim, 0, PS_SUPPORT_ROTATION, PS_AXIS_Y) == PS_OK);
  int32_t equilibrium = 0;
  CHECK(ps_sim_settle(sim, 5, &equilibrium) == PS_OK && equilibrium);
  CHECK(ps_sim_get_handle_reaction(sim, 0, 0, &r) == PS_OK);
  CHECK(fabs(r.force[1] - weight) < 1e-6 * weight);
  CHECK(fabs(r.force[0]) < 1e-9 * weight && fabs(r.force[2]) < 1e-9 * weight);
  double top_row[3 * 441];
  size_t got = 0;
  CHECK(ps_sim_get_positions(sim, 0, top_row, 3 * 441, &got) == PS_OK);
  for (int32_t i = 0; i < 21; ++i) /* the rest position of vertex 420 + i is (i / 20, 1, 0) */
    CHECK(fabs(top_row[3 * (420 + i)] - i / 20.0) < 1e-9 &&
          fabs(top_row[3 * (420 + i) + 2]) < 1e-9);
  ps_sim_destroy(sim);
  ps_hierarchy_destroy(h);
}

static void test_misuse(void) {
  ps_hierarchy* h = NULL;
  ps_sim* sim = NULL;
  int32_t levels = 0;
  size_t count = 0;
  CHECK_ERROR(ps_hierarchy_num_levels(NULL, &levels), PS_ERROR_NULL_ARGUMENT, ps_last_error(),
              "hierarchy is NULL");
  CHECK_ERROR(ps_sim_step_preview(NULL, 1), PS_ERROR_NULL_ARGUMENT, ps_last_error(), "sim is NULL");
  CHECK(strstr(ps_sim_last_error(NULL), "sim is NULL") != NULL);
  ps_sim_destroy(NULL);
  ps_hierarchy_destroy(NULL);

  double nan_vertices[27];
  memcpy(nan_vertices, kGridVertices, sizeof nan_vertices);
  nan_vertices[3 * 4 + 1] = NAN;
  CHECK_ERROR(ps_hierarchy_create(NULL, nan_vertices, 9, kGridFaces, 8, &h), PS_ERROR_INVALID_MESH,
              ps_last_error(), "vertex 4");
  CHECK(h == NULL);
  int32_t bad_faces[24];
  memcpy(bad_faces, kGridFaces, sizeof bad_faces);
  bad_faces[5] = 9;
  CHECK_ERROR(ps_hierarchy_create(NULL, kGridVertices, 9, bad_faces, 8, &h), PS_ERROR_INVALID_MESH,
              ps_last_error(), "9");
  ps_hierarchy_def hdef;
  memset(&hdef, 0, sizeof hdef);
  CHECK_ERROR(ps_hierarchy_create(&hdef, kGridVertices, 9, kGridFaces, 8, &h),
              PS_ERROR_UNINITIALIZED_DEF, ps_last_error(), "ps_hierarchy_def_init");
  ps_hierarchy_def_init(&hdef);
  const int32_t coarse[1] = {9};
  hdef.coarse_vertex_counts = coarse;
  hdef.num_coarse_levels = 1;
  CHECK_ERROR(ps_hierarchy_create(&hdef, kGridVertices, 9, kGridFaces, 8, &h),
              PS_ERROR_INVALID_ARGUMENT, ps_last_error(), "below the mesh's 9 vertices");
  hdef.coarse_vertex_counts = NULL;
  CHECK_ERROR(ps_hierarchy_create(&hdef, kGridVertices, 9, kGridFaces, 8, &h),
              PS_ERROR_NULL_ARGUMENT, ps_last_error(), "coarse_vertex_counts");
  CHECK_ERROR(ps_hierarchy_load("/nonexistent/h.bin", &h), PS_ERROR_IO, ps_last_error(),
              "/nonexistent/h.bin");
  CHECK_ERROR(ps_hierarchy_create_from_file(NULL, "/nonexistent/mesh.obj", &h), PS_ERROR_IO,
              ps_last_error(), "/nonexistent/mesh.obj");

  CHECK(ps_hierarchy_create(NULL, kGridVertices, 9, kGridFaces, 8, &h) == PS_OK);
  if (!h) return;
  CHECK_ERROR(ps_hierarchy_level_size(h, 1, NULL, NULL), PS_ERROR_OUT_OF_RANGE,
              ps_hierarchy_last_error(h), "level 1 does not exist");
  double small[6];
  CHECK_ERROR(ps_hierarchy_get_rest_positions(h, 0, small, 6, &count), PS_ERROR_BUFFER_TOO_SMALL,
              ps_hierarchy_last_error(h), "27 are needed");

  ps_sim_def def;
  memset(&def, 0, sizeof def);
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_UNINITIALIZED_DEF, ps_last_error(),
              "ps_sim_def_init");
  ps_sim_def_init(&def);
  def.material_poisson_ratio = 0.5;
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_INVALID_ARGUMENT, ps_last_error(),
              "material.poisson_ratio");
  ps_sim_def_init(&def);
  CHECK(def.solver_max_cg_iterations == 0); /* CG refinement is opt-in */
  def.solver_max_cg_iterations = -1;
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_INVALID_ARGUMENT, ps_last_error(),
              "solver.max_cg_iterations");
  ps_sim_def_init(&def);
  CHECK(def.solver_line_search_extrapolation == 1); /* on by default */
  def.solver_line_search_extrapolation = 2;
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_INVALID_ARGUMENT, ps_last_error(),
              "solver.line_search_extrapolation");
  ps_sim_def_init(&def);
  const int32_t out_of_range[1] = {99};
  def.pinned_vertices = out_of_range;
  def.num_pinned_vertices = 1;
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_INVALID_SCENE, ps_last_error(), "vertex 99");
  CHECK(sim == NULL);

  CHECK(ps_sim_create(h, NULL, &sim) == PS_OK);
  if (!sim) return;
  CHECK_ERROR(ps_sim_set_param(sim, "material.thicknes", 1e-3), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "unknown parameter 'material.thicknes'");
  CHECK_ERROR(ps_sim_set_param(sim, "material.thickness", NAN), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "material.thickness");
  CHECK_ERROR(ps_sim_set_param(sim, "simulation.time_step", -1), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "simulation.time_step");
  double value = 0;
  CHECK(ps_sim_get_param(sim, "simulation.time_step", &value) == PS_OK && value == 0.01);
  CHECK_ERROR(ps_sim_set_effect(sim, 3, 1), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "single ps_effect bit");
  CHECK_ERROR(ps_sim_step_preview(sim, 0), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "steps = 0");
  CHECK_ERROR(ps_sim_get_positions(sim, 2, NULL, 0, &count), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim), "level 2 does not exist");
  CHECK_ERROR(ps_sim_get_positions(sim, 0, NULL, 0, NULL), PS_ERROR_NULL_ARGUMENT,
              ps_sim_last_error(sim), "count is NULL");
  CHECK_ERROR(ps_sim_set_handle_motion(sim, 0, NULL, NULL, NULL, 0, NULL), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim), "handle 0 does not exist");
  CHECK_ERROR(ps_sim_write_mesh(sim, 0, "/nonexistent/dir/out.obj"), PS_ERROR_IO,
              ps_sim_last_error(sim), "/nonexistent/dir/out.obj");
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  CHECK(strcmp(ps_sim_last_error(sim), "") == 0); /* success clears the message */
  ps_sim_destroy(sim);
  ps_hierarchy_destroy(h);

  sim = NULL;
  CHECK_ERROR(ps_sim_create_from_scene("{\"bodies\": [], \"efects\": []}", NULL, &sim),
              PS_ERROR_INVALID_SCENE, ps_last_error(), "efects");
  CHECK_ERROR(ps_sim_create_from_scene("{ not json", NULL, &sim), PS_ERROR_INVALID_SCENE,
              ps_last_error(), "");
  /* A cloth cutting through an obstacle box is rejected, naming the crossing faces. */
  CHECK_ERROR(ps_sim_create_from_scene(
                  "{\"effects\": [\"membrane\", \"contact\"], \"bodies\": [{\"mesh\": "
                  "{\"generator\": \"grid\", \"width\": 1, \"height\": 1, \"nx\": 2, "
                  "\"ny\": 2}}], \"obstacles\": [{\"mesh\": {\"generator\": \"box\", "
                  "\"size\": [0.5, 0.5, 0.5]}, \"transform\": {\"translate\": [0.5, 0.5, 0]}}]}",
                  NULL, &sim),
              PS_ERROR_INTERSECTING, ps_last_error(), "obstacle face");
  CHECK_ERROR(ps_sim_create_from_scene("{\"effects\": [\"contact\"], \"contact\": "
                                       "{\"dhat\": 0}, \"bodies\": [{\"mesh\": "
                                       "{\"generator\": \"grid\", \"width\": 1, "
                                       "\"height\": 1, \"nx\": 2, \"ny\": 2}}]}",
                                       NULL, &sim),
              PS_ERROR_INVALID_SCENE, ps_last_error(), "dhat");
  CHECK(sim == NULL);
}

static void test_parameter_listing_mode_and_lifetimes(void) {
  const int32_t n = ps_param_count();
  CHECK(n >= 13);
  int found = 0;
  for (int32_t i = 0; i < n; ++i) {
    ps_param_info info;
    CHECK(ps_param_info_get(i, &info) == PS_OK);
    if (strcmp(info.name, "material.thickness") == 0)
      found = strcmp(info.unit, "m") == 0 && info.default_value == 1e-3 && info.min == 0.0 &&
              !info.min_inclusive;
  }
  CHECK(found);
  ps_param_info info;
  CHECK_ERROR(ps_param_info_get(n, &info), PS_ERROR_OUT_OF_RANGE, ps_last_error(),
              "does not exist");

  ps_hierarchy* h = NULL;
  ps_sim* sim = NULL;
  CHECK(ps_hierarchy_create(NULL, kGridVertices, 9, kGridFaces, 8, &h) == PS_OK);
  CHECK(ps_sim_create(h, NULL, &sim) == PS_OK);
  if (!h || !sim) return;
  int32_t mode = -1;
  CHECK(ps_sim_get_mode(sim, &mode) == PS_OK && mode == PS_MODE_DYNAMIC);
  /* Quasistatic, the unpinned sheet under gravity has no equilibrium: refused, naming it. */
  CHECK_ERROR(ps_sim_set_mode(sim, PS_MODE_QUASISTATIC), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "is free in a quasistatic scene");
  CHECK(ps_sim_get_mode(sim, &mode) == PS_OK && mode == PS_MODE_DYNAMIC);
  CHECK(ps_sim_set_effect(sim, PS_EFFECT_GRAVITY, 0) == PS_OK);
  CHECK(ps_sim_set_mode(sim, PS_MODE_QUASISTATIC) == PS_OK);
  CHECK(ps_sim_get_mode(sim, &mode) == PS_OK && mode == PS_MODE_QUASISTATIC);
  CHECK_ERROR(ps_sim_set_mode(sim, 7), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "not a ps_mode");
  /* The hierarchy outlives its simulations: destroying it first is refused, not UB. */
  CHECK_ERROR(ps_hierarchy_destroy(h), PS_ERROR_WRONG_CALL_ORDER, ps_last_error(),
              "1 simulation(s) still use this hierarchy");
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  ps_sim_destroy(sim);
  CHECK(ps_hierarchy_destroy(h) == PS_OK);
  CHECK(ps_hierarchy_destroy(NULL) == PS_OK);
}

static void test_scene_file(void) {
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene_file(path_in_source("scenes/hanging_cloth.json"), &sim) == PS_OK);
  if (!sim) return;
  const ps_hierarchy* h = NULL;
  size_t nv = 0;
  CHECK(ps_sim_hierarchy(sim, &h) == PS_OK && h != NULL);
  CHECK(ps_hierarchy_level_size(h, 0, &nv, NULL) == PS_OK && nv > 0);
  int32_t handles = 0;
  CHECK(ps_sim_num_handles(sim, &handles) == PS_OK && handles >= 1);
  CHECK(ps_sim_step_preview(sim, 2) == PS_OK);
  ps_sim_destroy(sim);
}

/* A quasistatic 1 m sheet (4 × 4 quads) whose handle 0 holds its left edge, with `motion` as
 * the handle's JSON motion. */
static ps_sim* keyframed_sheet(const char* motion) {
  char json[1024];
  snprintf(json, sizeof json,
           "{\"simulation\": {\"mode\": \"quasistatic\", \"time_step\": 0.1},"
           " \"effects\": [\"membrane\", \"bending\"], \"bodies\": [{\"mesh\": {\"generator\":"
           " \"grid\", \"width\": 1, \"height\": 1, \"nx\": 4, \"ny\": 4}}],"
           " \"handles\": [{\"body\": 0, \"vertices\": [0, 5, 10, 15, 20], \"motion\": %s}]}",
           motion);
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene(json, NULL, &sim) == PS_OK);
  return sim;
}

/* Keyframes through the C ABI: each key's pose at its time, the same steps bit for bit as the
 * scene's "keyframes", and bad keys refused naming the key with the motion unchanged. */
static void test_handle_keyframes(void) {
  /* rows: time, tx, ty, tz, ax, ay, az, angle; a quarter turn about z through c = (0, 0.5, 0) */
  const double rows[3 * 8] = {0.0, 0, 0, 0, 0,   0, 1, 0,   0.2, 0, 0, 0.1,
                              0,   0, 1, 0, 0.4, 0, 0, 0.1, 0,   0, 1, 1.5707963267948966};
  ps_sim* coded = keyframed_sheet("{\"center\": [0, 0.5, 0]}");
  ps_sim* read = keyframed_sheet(
      "{\"center\": [0, 0.5, 0], \"interpolation\": \"smooth\", \"keyframes\": ["
      "{\"time\": 0}, {\"time\": 0.2, \"translation\": [0, 0, 0.1]}, {\"time\": 0.4, "
      "\"translation\": [0, 0, 0.1], \"angle\": 1.5707963267948966}]}");
  if (!coded || !read) return;
  CHECK(ps_sim_set_handle_keyframes(coded, 0, rows, 3, PS_INTERPOLATION_SMOOTH) == PS_OK);
  double a[3 * 25], b[3 * 25];
  size_t count = 0;
  for (int step = 1; step <= 5; ++step) {
    CHECK(ps_sim_step_preview(coded, 1) == PS_OK && ps_sim_step_preview(read, 1) == PS_OK);
    CHECK(ps_sim_get_positions(coded, 0, a, 75, &count) == PS_OK && count == 75);
    CHECK(ps_sim_get_positions(read, 0, b, 75, &count) == PS_OK);
    CHECK(memcmp(a, b, sizeof a) == 0); /* the scene's keyframes, bit for bit */
    if (step == 2)                      /* key 1: vertex 20 (0, 1, 0) lifted by 0.1 */
      CHECK(fabs(a[60]) < 1e-12 && fabs(a[61] - 1.0) < 1e-12 && fabs(a[62] - 0.1) < 1e-12);
    if (step >= 4) /* key 2 and after: turned a quarter about z through (0, 0.5, 0) */
      CHECK(fabs(a[60] + 0.5) < 1e-12 && fabs(a[61] - 0.5) < 1e-12 && fabs(a[62] - 0.1) < 1e-12);
  }

  const double late[2 * 8] = {0.5, 0, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 0, 0, 0, 1, 0};
  CHECK_ERROR(ps_sim_set_handle_keyframes(coded, 0, late, 2, PS_INTERPOLATION_LINEAR),
              PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(coded),
              "handles[0].motion.keyframes[1].time");
  double bad[8] = {0.0, 0, 0, 0, 0, 0, 0, 0}; /* zero axis */
  CHECK_ERROR(ps_sim_set_handle_keyframes(coded, 0, bad, 1, PS_INTERPOLATION_LINEAR),
              PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(coded), "keyframes[0].axis");
  bad[6] = 1.0;
  bad[1] = NAN;
  CHECK_ERROR(ps_sim_set_handle_keyframes(coded, 0, bad, 1, PS_INTERPOLATION_LINEAR),
              PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(coded), "keyframes[0].translation");
  CHECK_ERROR(ps_sim_set_handle_keyframes(coded, 0, rows, 3, 7), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(coded), "not a ps_interpolation");
  CHECK_ERROR(ps_sim_set_handle_keyframes(coded, 0, rows, 0, PS_INTERPOLATION_LINEAR),
              PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(coded), "num_rows = 0");
  CHECK_ERROR(ps_sim_set_handle_keyframes(coded, 0, NULL, 3, PS_INTERPOLATION_LINEAR),
              PS_ERROR_NULL_ARGUMENT, ps_sim_last_error(coded), "rows");
  CHECK_ERROR(ps_sim_set_handle_keyframes(coded, 1, rows, 3, PS_INTERPOLATION_LINEAR),
              PS_ERROR_OUT_OF_RANGE, ps_sim_last_error(coded), "handle 1 does not exist");
  /* refused calls changed nothing: both still step alike */
  CHECK(ps_sim_step_preview(coded, 1) == PS_OK && ps_sim_step_preview(read, 1) == PS_OK);
  CHECK(ps_sim_get_positions(coded, 0, a, 75, &count) == PS_OK);
  CHECK(ps_sim_get_positions(read, 0, b, 75, &count) == PS_OK);
  CHECK(memcmp(a, b, sizeof a) == 0);
  ps_sim_destroy(coded);
  ps_sim_destroy(read);
}

/* Counts progress reports; cancels once `cancel_at` percent is reached (if positive). */
static int32_t count_reports(void* user_data, int32_t done, int32_t total, const char* phase) {
  int32_t* state = (int32_t*)user_data; /* [reports, cancel_at] */
  (void)phase;
  ++state[0];
  return state[1] > 0 && done * 100 >= state[1] * total;
}

/* A decimated hierarchy: sizes, exact rest recovery through ps_hierarchy_prolong, progress,
 * cancellation, save/load, and a progressive animation by default on it. */
static void test_levels(void) {
  ps_hierarchy_def hdef;
  ps_hierarchy_def_init(&hdef);
  const int32_t coarse[2] = {30, 110};
  int32_t progress[2] = {0, 0};
  hdef.coarse_vertex_counts = coarse;
  hdef.num_coarse_levels = 2;
  hdef.progress = count_reports;
  hdef.progress_user_data = progress;
  ps_hierarchy* h = NULL;
  const char* mesh = path_in_source("scenes/meshes/square_cloth.obj");
  CHECK(ps_hierarchy_create_from_file(&hdef, mesh, &h) == PS_OK);
  if (!h) return;
  CHECK(progress[0] > 10);
  int32_t levels = 0, batches = 0;
  size_t nv = 0, count = 0;
  CHECK(ps_hierarchy_num_levels(h, &levels) == PS_OK && levels == 3);
  CHECK(ps_hierarchy_level_size(h, 0, &nv, NULL) == PS_OK && nv == 30);
  CHECK(ps_hierarchy_num_expansion_batches(h, 0, &batches) == PS_OK && batches > 0);
  CHECK_ERROR(ps_hierarchy_num_expansion_batches(h, 2, &batches), PS_ERROR_OUT_OF_RANGE,
              ps_hierarchy_last_error(h), "finest");
  double coarse_rest[90], fine[3 * 441], prolonged[3 * 441];
  CHECK(ps_hierarchy_get_rest_positions(h, 0, coarse_rest, 90, &count) == PS_OK);
  CHECK(ps_hierarchy_get_rest_positions(h, 2, fine, 3 * 441, &count) == PS_OK);
  CHECK(ps_hierarchy_prolong(h, 0, coarse_rest, 90, prolonged, 3 * 441, &count) == PS_OK);
  double worst = 0.0;
  for (size_t i = 0; i < 3 * 441; ++i) worst = fmax(worst, fabs(prolonged[i] - fine[i]));
  CHECK(count == 3 * 441 && worst < 1e-9);
  CHECK_ERROR(ps_hierarchy_prolong(h, 0, coarse_rest, 89, prolonged, 3 * 441, &count),
              PS_ERROR_INVALID_ARGUMENT, ps_hierarchy_last_error(h), "needs 90");
  ps_sim* sim = NULL; /* the default mode is dynamic: a progressive animation */
  int32_t kind = -1, frames = 0;
  CHECK(ps_sim_create(h, NULL, &sim) == PS_OK);
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_PROGRESSIVE_DYNAMICS);
  CHECK(ps_sim_step_preview(sim, 2) == PS_OK && ps_sim_refine(sim) == PS_OK);
  CHECK(ps_sim_num_frames(sim, 1, &frames) == PS_OK && frames == 3);
  ps_sim_destroy(sim);

  char saved[4096];
  snprintf(saved, sizeof saved, "%s/test_capi_levels.hierarchy",
           getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  CHECK(ps_hierarchy_save(h, saved) == PS_OK);
  ps_hierarchy* loaded = NULL;
  CHECK(ps_hierarchy_load(saved, &loaded) == PS_OK);
  double again[3 * 441];
  CHECK(ps_hierarchy_prolong(loaded, 0, coarse_rest, 90, again, 3 * 441, &count) == PS_OK);
  CHECK(memcmp(again, prolonged, sizeof again) == 0);
  remove(saved);
  ps_hierarchy_destroy(loaded);
  ps_hierarchy_destroy(h);

  progress[1] = 50;
  h = NULL;
  CHECK_ERROR(ps_hierarchy_create_from_file(&hdef, mesh, &h), PS_ERROR_CANCELLED, ps_last_error(),
              "cancelled");
  CHECK(h == NULL);
}

/* A progressive (PSQ) simulation through the ABI: a cloth hanging from its top row (in its own
 * plane, so the equilibrium is a stretched cloth), previewed on level 0, refined to the finest
 * level and settled there; errors of the coarse levels against the converged result. */
/* With self-contact, refinement is PSQ §4.4's safe expansion: every split of the hierarchy's
 * record between the two levels is made, in batches, and its statistics reach the ABI. */
static void check_refinement_stats(const ps_hierarchy* h, ps_sim_def def) {
  def.effects |= PS_EFFECT_CONTACT;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  if (!sim) return;
  int32_t equilibrium = 0;
  size_t coarse = 0, fine = 0;
  CHECK(ps_hierarchy_level_size(h, 0, &coarse, NULL) == PS_OK);
  CHECK(ps_hierarchy_level_size(h, 1, &fine, NULL) == PS_OK);
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  CHECK(ps_sim_refine(sim) == PS_OK);
  CHECK(ps_sim_settle(sim, 300, &equilibrium) == PS_OK && equilibrium == 1);
  ps_level_stats stats;
  CHECK(ps_sim_get_level_stats(sim, 1, &stats) == PS_OK);
  CHECK((size_t)stats.refinement.splits == fine - coarse && stats.refinement.batches >= 1);
  CHECK(stats.refinement.rounds >= stats.refinement.batches);
  CHECK(stats.refinement.reached > 0.0 && stats.refinement.reached <= 1.0);
  CHECK(stats.refinement.min_gap > 0.0 && stats.reduced_offsets == 0);
  ps_sim_destroy(sim);
}

/* Issue 28's one rule: a finest mesh that crosses itself, with contact on, is refused before any
 * work by ps_sim_create and ps_sim_create_from_scene_file, naming a crossing pair of the input,
 * whatever its coarse levels; contact_crossing_start = 1 lets a progressive simulation start. */
static void test_crossing_input(void) {
  ps_sim* sim = NULL;
  CHECK_ERROR(ps_sim_create_from_scene_file(path_in_source("tests/data/crossing_flap.json"), &sim),
              PS_ERROR_INTERSECTING, ps_last_error(), "crossing_flap: the input mesh: shell face");
  CHECK(sim == NULL);
  ps_hierarchy_def hdef;
  ps_hierarchy_def_init(&hdef);
  const int32_t coarse[2] = {40, 100};
  hdef.coarse_vertex_counts = coarse;
  hdef.num_coarse_levels = 2;
  ps_hierarchy* h = NULL;
  CHECK(ps_hierarchy_create_from_file(&hdef, path_in_source("tests/data/crossing_flap.obj"), &h) ==
        PS_OK);
  if (!h) return;
  /* The hierarchy's contact offset: checked, and kept by the levels it builds. */
  CHECK(hdef.contact_offset == 0.0);
  hdef.contact_offset = -1e-3;
  ps_hierarchy* bad = NULL;
  CHECK_ERROR(
      ps_hierarchy_create_from_file(&hdef, path_in_source("tests/data/crossing_flap.obj"), &bad),
      PS_ERROR_INVALID_ARGUMENT, ps_last_error(), "contact_offset = -0.001");
  CHECK(bad == NULL);
  hdef.contact_offset = 2.5e-4;
  CHECK(ps_hierarchy_create_from_file(&hdef, path_in_source("tests/data/crossing_flap.obj"),
                                      &bad) == PS_OK);
  ps_hierarchy_destroy(bad);
  ps_sim_def def;
  ps_sim_def_init(&def);
  CHECK(def.contact_crossing_start == 0);
  def.mode = PS_MODE_QUASISTATIC;
  def.simulation_time_step = 1.0;
  def.effects = PS_EFFECT_MEMBRANE | PS_EFFECT_BENDING | PS_EFFECT_CONTACT;
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_INTERSECTING, ps_last_error(),
              "the input mesh: shell face");
  CHECK(sim == NULL);
  def.contact_crossing_start = 1;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  ps_sim_destroy(sim);
  def.contact_crossing_start = 2;
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_INVALID_ARGUMENT, ps_last_error(),
              "contact.crossing_start");
  ps_hierarchy_destroy(h);
}

static void test_progressive(void) {
  int32_t top_row[21];
  for (int i = 0; i < 21; ++i) top_row[i] = 420 + i; /* y = 1 in square_cloth.obj */
  ps_hierarchy_def hdef;
  ps_hierarchy_def_init(&hdef);
  const int32_t coarse[2] = {40, 120};
  hdef.coarse_vertex_counts = coarse;
  hdef.num_coarse_levels = 2;
  hdef.pinned_vertices = top_row;
  hdef.num_pinned_vertices = 21;
  ps_hierarchy* h = NULL;
  CHECK(ps_hierarchy_create_from_file(&hdef, path_in_source("scenes/meshes/square_cloth.obj"),
                                      &h) == PS_OK);
  if (!h) return;
  ps_sim_def def;
  ps_sim_def_init(&def);
  def.mode = PS_MODE_QUASISTATIC;
  def.simulation_time_step = 1.0;
  def.pinned_vertices = top_row;
  def.num_pinned_vertices = 20; /* one short of the hierarchy's */
  ps_sim* sim = NULL;
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_INVALID_ARGUMENT, ps_last_error(),
              "pinned_vertices");
  def.num_pinned_vertices = 21;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  if (!sim) {
    ps_hierarchy_destroy(h);
    return;
  }
  int32_t level = -1, equilibrium = 0;
  size_t count = 0;
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  CHECK(ps_sim_settle(sim, 300, &equilibrium) == PS_OK && equilibrium == 1);
  CHECK(ps_sim_get_positions(sim, 2, NULL, 0, &count) == PS_OK && count == 3 * 441);
  ps_level_stats stats;
  CHECK(ps_sim_get_level_stats(sim, 0, &stats) == PS_OK && isnan(stats.error_rms));
  CHECK(stats.steps == 1 && stats.settles >= 1 && stats.equilibrium == 1);
  CHECK(ps_sim_refine(sim) == PS_OK);
  CHECK(ps_sim_current_level(sim, &level) == PS_OK && level == 1);
  CHECK(ps_sim_settle(sim, 300, &equilibrium) == PS_OK && equilibrium == 1);
  CHECK(ps_sim_refine(sim) == PS_OK);
  CHECK(ps_sim_settle(sim, 50, &equilibrium) == PS_OK && equilibrium == 1);
  CHECK(ps_sim_get_level_stats(sim, 1, &stats) == PS_OK && stats.refine_seconds > 0.0);
  CHECK(stats.error_max >= stats.error_rms && stats.error_max < 0.05);
  CHECK(ps_sim_get_level_stats(sim, 2, &stats) == PS_OK && stats.error_max == 0.0);
  /* No contact: the prolonged state is the start, no safe expansion ran. */
  CHECK(stats.refinement.batches == 0 && stats.refinement.splits == 0);
  CHECK(stats.reduced_offsets == 0 && stats.raised_limits == 0);
  CHECK_ERROR(ps_sim_refine(sim), PS_ERROR_OUT_OF_RANGE, ps_sim_last_error(sim), "finest");
  check_refinement_stats(h, def);
  CHECK_ERROR(ps_sim_settle(sim, 0, NULL), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "max_solves");
  ps_sim_destroy(sim);
  ps_hierarchy_destroy(h);
}

/* On a two-level scene: `steps` preview steps, equilibrium on the coarse level, refinement,
 * equilibrium on the finest; the two levels' statistics into *coarse and *fine. */
static void preview_then_refine_once(ps_sim* sim, int32_t steps, ps_level_stats* coarse,
                                     ps_level_stats* fine) {
  int32_t equilibrium = 0;
  CHECK(ps_sim_step_preview(sim, steps) == PS_OK);
  CHECK(ps_sim_settle(sim, 300, &equilibrium) == PS_OK && equilibrium == 1);
  CHECK(ps_sim_refine(sim) == PS_OK);
  CHECK(ps_sim_settle(sim, 300, &equilibrium) == PS_OK && equilibrium == 1);
  CHECK(ps_sim_get_level_stats(sim, 0, coarse) == PS_OK);
  CHECK(ps_sim_get_level_stats(sim, 1, fine) == PS_OK);
}

/* solver.max_cg_iterations through the ABI: read from the scene's solver section, checked by
 * ps_sim_set_param, and counted per level: never in the coarse level's proxy solves (their
 * Hessian only preconditions), on the finest level where the wrung cloth's Hessian is
 * indefinite. */
static void test_cg_refinement(void) {
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene_file(path_in_source("tests/data/twist_cg_refined.json"), &sim) ==
        PS_OK);
  if (!sim) return;
  double value = 0.0;
  CHECK(ps_sim_get_param(sim, "solver.max_cg_iterations", &value) == PS_OK && value == 50.0);
  CHECK_ERROR(ps_sim_set_param(sim, "solver.max_cg_iterations", 2.5), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "solver.max_cg_iterations");
  ps_level_stats coarse, fine;
  preview_then_refine_once(sim, 6, &coarse, &fine);
  CHECK(coarse.newton_iterations > 0 && coarse.cg_iterations == 0);
  CHECK(fine.newton_iterations > 0 && fine.cg_iterations > 0);
  ps_sim_destroy(sim);
}

/* Newton steps the line search lengthened on the twist's coarse level over 6 preview steps,
 * with solver.line_search_extrapolation set to `on` (1 or 0) through the ABI. */
static int32_t extrapolated_preview_steps(double on) {
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene_file(path_in_source("tests/data/twist_cg_refined.json"), &sim) ==
        PS_OK);
  if (!sim) return -1;
  double value = -1.0;
  CHECK(ps_sim_get_param(sim, "solver.line_search_extrapolation", &value) == PS_OK && value == 1.0);
  CHECK(ps_sim_set_param(sim, "solver.line_search_extrapolation", on) == PS_OK);
  CHECK_ERROR(ps_sim_set_param(sim, "solver.line_search_extrapolation", 0.5),
              PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "solver.line_search_extrapolation");
  ps_level_stats stats;
  CHECK(ps_sim_step_preview(sim, 6) == PS_OK);
  CHECK(ps_sim_get_level_stats(sim, 0, &stats) == PS_OK);
  ps_sim_destroy(sim);
  return stats.extrapolated_steps;
}

/* solver.line_search_extrapolation through the ABI: on by default, where the twist's coarse
 * steps are lengthened; off, none is. */
static void test_extrapolation_switch(void) {
  CHECK(extrapolated_preview_steps(1.0) > 0);
  CHECK(extrapolated_preview_steps(0.0) == 0);
}

/* The accuracy-vs-time numbers through the ABI, on the bundled plate-buckling scene. */
static void test_accuracy(void) {
  ps_accuracy* accuracy = NULL;
  CHECK(ps_accuracy_run_scene_file(path_in_source("scenes/psq_plate_buckling.json"), NULL,
                                   &accuracy) == PS_OK);
  if (!accuracy) return;
  int32_t rows = 0;
  CHECK(ps_accuracy_num_rows(accuracy, &rows) == PS_OK && rows == 6);
  ps_accuracy_row row;
  CHECK(ps_accuracy_get_row(accuracy, 0, &row) == PS_OK);
  CHECK(row.method == PS_METHOD_PROGRESSIVE && row.level == 0 && row.seconds > 0.0);
  CHECK(row.error_max > 0.0 && row.error_max < 0.1);
  CHECK(row.intersecting_pairs == 0 && row.converged == 1);
  CHECK(row.load_steps == 10 && row.finished == 1); /* the scene's 10 load steps */
  CHECK(ps_accuracy_get_row(accuracy, 5, &row) == PS_OK);
  CHECK(row.method == PS_METHOD_DIRECT && row.level == 2 && row.vertices == 625);
  CHECK(row.intersecting_pairs == 0 && row.converged == 1);
  CHECK(row.load_steps == 10 && row.finished == 1);
  CHECK_ERROR(ps_accuracy_get_row(accuracy, 6, &row), PS_ERROR_OUT_OF_RANGE, ps_last_error(),
              "6 rows");
  char dir[4096];
  snprintf(dir, sizeof dir, "%s/test_capi_accuracy", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  CHECK(ps_accuracy_write(accuracy, dir) == PS_OK);
  char csv[4200];
  snprintf(csv, sizeof csv, "%s/accuracy.csv", dir);
  FILE* file = fopen(csv, "r");
  CHECK(file != NULL);
  if (file) fclose(file);
  ps_accuracy_destroy(accuracy);
  accuracy = NULL;
  CHECK_ERROR(
      ps_accuracy_run_scene_file(path_in_source("scenes/hanging_cloth.json"), NULL, &accuracy),
      PS_ERROR_INVALID_SCENE, ps_last_error(), "coarse levels");
  CHECK(accuracy == NULL);
}

/* ps_accuracy_def: only the levels named are solved directly, a direct solve past its time limit
 * is reported unfinished, progress is reported, and defs that make no sense are refused. */
static void test_accuracy_def(void) {
  const char* plate = path_in_source("scenes/psq_plate_buckling.json");
  const int32_t finest[1] = {2};
  int32_t progress[2] = {0, 0};
  ps_accuracy_def def;
  ps_accuracy_def_init(&def);
  def.direct_levels = finest;
  def.num_direct_levels = 1;
  def.direct_time_ratio = 1e-9; /* stops before the script is done */
  def.progress = count_reports;
  def.progress_user_data = progress;
  ps_accuracy* accuracy = NULL;
  CHECK(ps_accuracy_run_scene_file(plate, &def, &accuracy) == PS_OK);
  int32_t rows = 0;
  CHECK(accuracy && ps_accuracy_num_rows(accuracy, &rows) == PS_OK && rows == 4);
  ps_accuracy_row row;
  CHECK(accuracy && ps_accuracy_get_row(accuracy, 3, &row) == PS_OK);
  CHECK(row.method == PS_METHOD_DIRECT && row.level == 2);
  CHECK(row.finished == 0 && row.converged == 0 && row.load_steps < 10);
  CHECK(progress[0] > 10);  /* phases and the preview's 10 load steps at least */
  ps_accuracy_row pipeline; /* the progressive finest row: the default base of the limit */
  double limit = -1.0;
  CHECK(accuracy && ps_accuracy_get_row(accuracy, 2, &pipeline) == PS_OK);
  CHECK(accuracy && ps_accuracy_direct_time_limit(accuracy, &limit) == PS_OK);
  CHECK(limit == 1e-9 * pipeline.seconds);
  ps_accuracy_destroy(accuracy);
  /* Relative to the preview: the direct finest solve gets twice the coarse preview's time. */
  ps_accuracy_def of_preview = def;
  of_preview.direct_time_ratio = 2.0;
  of_preview.direct_time_base = PS_TIME_BASE_PREVIEW;
  accuracy = NULL;
  CHECK(ps_accuracy_run_scene_file(plate, &of_preview, &accuracy) == PS_OK);
  ps_accuracy_row preview;
  CHECK(accuracy && ps_accuracy_get_row(accuracy, 0, &preview) == PS_OK);
  CHECK(accuracy && ps_accuracy_direct_time_limit(accuracy, &limit) == PS_OK);
  CHECK(preview.method == PS_METHOD_PROGRESSIVE && preview.level == 0);
  CHECK(limit == 2.0 * preview.seconds);
  CHECK_ERROR(ps_accuracy_direct_time_limit(accuracy, NULL), PS_ERROR_NULL_ARGUMENT,
              ps_last_error(), "out");
  ps_accuracy_destroy(accuracy);
  ps_accuracy_def bad = def;
  const int32_t missing[1] = {3};
  bad.direct_levels = missing;
  accuracy = NULL;
  CHECK_ERROR(ps_accuracy_run_scene_file(plate, &bad, &accuracy), PS_ERROR_INVALID_ARGUMENT,
              ps_last_error(), "direct level 3 does not exist");
  bad = def;
  bad.direct_time_ratio = -1.0;
  CHECK_ERROR(ps_accuracy_run_scene_file(plate, &bad, &accuracy), PS_ERROR_INVALID_ARGUMENT,
              ps_last_error(), "time ratio");
  bad = def;
  bad.direct_time_base = (ps_time_base)7;
  CHECK_ERROR(ps_accuracy_run_scene_file(plate, &bad, &accuracy), PS_ERROR_INVALID_ARGUMENT,
              ps_last_error(), "direct_time_base 7");
  bad = def;
  bad.direct_levels = NULL;
  CHECK_ERROR(ps_accuracy_run_scene_file(plate, &bad, &accuracy), PS_ERROR_NULL_ARGUMENT,
              ps_last_error(), "direct_levels");
  memset(&bad, 0, sizeof bad);
  CHECK_ERROR(ps_accuracy_run_scene_file(plate, &bad, &accuracy), PS_ERROR_UNINITIALIZED_DEF,
              ps_last_error(), "ps_accuracy_def_init");
  CHECK(accuracy == NULL);
}

/* A progressive obstacle (PSQ §4.6): the coarse level meets a decimated copy of the sphere, the
 * finest the sphere itself, refined with the cloth. */
static void test_progressive_obstacle(void) {
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene_file(path_in_source("tests/data/progressive_obstacle.json"),
                                      &sim) == PS_OK);
  if (!sim) return;
  ps_level_stats coarse, fine;
  preview_then_refine_once(sim, 1, &coarse, &fine);
  CHECK(fine.obstacle_vertices == 162); /* the sphere's own vertices */
  CHECK(coarse.obstacle_vertices > 0 && coarse.obstacle_vertices < fine.obstacle_vertices);
  CHECK(coarse.obstacle_refinement.splits == 0);
  CHECK(fine.obstacle_refinement.splits == fine.obstacle_vertices - coarse.obstacle_vertices);
  CHECK(fine.obstacle_refinement.reached > 0.0 && fine.obstacle_refinement.reached <= 1.0);
  ps_sim_destroy(sim);
}

/* The bundled drape at 21 × 21 vertices (the file's 41 × 41 edited in place): refinement
 * stretches faces far beyond the cloth's strain limit of 1.06, and the strain correction (PSQ
 * §4.4.5) brings every one back under it; its statistics reach the ABI. */
static void test_strain_correction(void) {
  static char json[16384];
  FILE* file = fopen(path_in_source("scenes/psq_cloth_on_sphere.json"), "rb");
  CHECK(file != NULL);
  if (!file) return;
  const size_t size = fread(json, 1, sizeof json - 1, file);
  fclose(file);
  json[size] = '\0';
  char* grid = strstr(json, "\"nx\": 40, \"ny\": 40");
  CHECK(grid != NULL);
  if (!grid) return;
  memcpy(grid, "\"nx\": 20, \"ny\": 20", strlen("\"nx\": 20, \"ny\": 20"));
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene(json, path_in_source("scenes"), &sim) == PS_OK);
  if (!sim) return;
  int32_t equilibrium = 0;
  CHECK(ps_sim_step_preview(sim, 4) == PS_OK);
  CHECK(ps_sim_settle(sim, 300, &equilibrium) == PS_OK && equilibrium == 1);
  CHECK(ps_sim_refine(sim) == PS_OK);
  ps_level_stats coarse, fine;
  CHECK(ps_sim_get_level_stats(sim, 0, &coarse) == PS_OK);
  CHECK(ps_sim_get_level_stats(sim, 1, &fine) == PS_OK);
  CHECK(coarse.strain_correction.strained_faces == 0 &&
        coarse.strain_correction.stretch_before == 0);
  CHECK(fine.strain_correction.strained_faces > 0 && fine.strain_correction.over_limit_faces == 0);
  CHECK(fine.strain_correction.stretch_before > 1.06 &&
        fine.strain_correction.stretch_after < 1.06);
  CHECK(fine.strain_correction.newton_iterations > 0);
  ps_sim_destroy(sim);
}

/* A strip clamped on its first two columns, its last two on a second handle: a rotation
 * support free to translate (a guided end) from the scene key, or a plain clamp switched to
 * one by ps_sim_set_handle_support(). Both step bit for bit alike. */
static const char* guided_strip(const char* end_keys) {
  static char json[1024];
  snprintf(json, sizeof json,
           "{ \"simulation\": { \"mode\": \"quasistatic\" }, \"gravity\": [0, 0, -9.81],"
           "  \"effects\": [\"membrane\", \"bending\", \"gravity\"],"
           "  \"bodies\": [ { \"mesh\": { \"generator\": \"grid\", \"width\": 0.4,"
           "                  \"height\": 0.1, \"nx\": 8, \"ny\": 2 },"
           "                  \"material\": { \"youngs_modulus\": 1e9 } } ],"
           "  \"handles\": [ { \"body\": 0, \"vertices\": [0, 1, 9, 10, 18, 19] },"
           "                 { \"body\": 0, \"vertices\": [7, 8, 16, 17, 25, 26] %s } ] }",
           end_keys);
  return json;
}

static void test_rotation_support_round_trip(void) {
  ps_sim *keyed = NULL, *coded = NULL;
  CHECK(ps_sim_create_from_scene(guided_strip(", \"support\": \"rotation\", \"axes\": \"\""), NULL,
                                 &keyed) == PS_OK);
  CHECK(ps_sim_create_from_scene(guided_strip(""), NULL, &coded) == PS_OK);
  if (!keyed || !coded) return;
  CHECK(ps_sim_set_handle_support(coded, 1, PS_SUPPORT_ROTATION, 0) == PS_OK);
  double a[81], b[81];
  size_t count = 0;
  for (int step = 0; step < 2; ++step) {
    CHECK(ps_sim_step_preview(keyed, 1) == PS_OK && ps_sim_step_preview(coded, 1) == PS_OK);
    CHECK(ps_sim_get_positions(keyed, 0, a, 81, &count) == PS_OK && count == 81);
    CHECK(ps_sim_get_positions(coded, 0, b, 81, &count) == PS_OK && count == 81);
    CHECK(memcmp(a, b, sizeof a) == 0);
  }
  CHECK(a[3 * 26 + 2] < -1e-6 && fabs(a[3 * 26 + 2] - a[3 * 25 + 2]) < 1e-15); /* sank, level */
  ps_sim_destroy(keyed);
  ps_sim_destroy(coded);
}

/* Several vertex groups in one hierarchy: a PSQ simulation of two levels holds the top-left
 * corner as group 0 (ps_sim_def.pinned_vertices) and the top-right corner as group 1
 * (ps_sim_add_handle), the second dragged sideways, on every level. */
static void test_vertex_groups(void) {
  int32_t ids[441];
  for (int32_t v = 0; v < 441; ++v) ids[v] = -1;
  ids[420] = ids[421] = 0; /* the top row is y = 1: vertices 420 .. 440 */
  ids[439] = ids[440] = 1;
  ps_hierarchy_def hdef;
  ps_hierarchy_def_init(&hdef);
  const int32_t coarse[1] = {60};
  hdef.coarse_vertex_counts = coarse;
  hdef.num_coarse_levels = 1;
  hdef.vertex_group_ids = ids;
  hdef.num_vertex_group_ids = 440;
  const char* mesh = path_in_source("scenes/meshes/square_cloth.obj");
  ps_hierarchy* h = NULL;
  CHECK_ERROR(ps_hierarchy_create_from_file(&hdef, mesh, &h), PS_ERROR_INVALID_ARGUMENT,
              ps_last_error(), "num_vertex_group_ids = 440");
  hdef.num_vertex_group_ids = 441;
  ids[439] = ids[440] = 2; /* a gap: group 1 is empty */
  CHECK_ERROR(ps_hierarchy_create_from_file(&hdef, mesh, &h), PS_ERROR_INVALID_ARGUMENT,
              ps_last_error(), "group 1 has no vertex");
  ids[439] = ids[440] = 2147483647; /* far beyond any gapless group */
  CHECK_ERROR(ps_hierarchy_create_from_file(&hdef, mesh, &h), PS_ERROR_INVALID_ARGUMENT,
              ps_last_error(), "vertex_group_ids[439] = 2147483647");
  ids[439] = ids[440] = 1;
  const int32_t left[2] = {420, 421}, right[2] = {439, 440}, stray[1] = {0};
  hdef.pinned_vertices = left;
  hdef.num_pinned_vertices = 2;
  CHECK_ERROR(ps_hierarchy_create_from_file(&hdef, mesh, &h), PS_ERROR_INVALID_ARGUMENT,
              ps_last_error(), "not both");
  hdef.pinned_vertices = NULL;
  hdef.num_pinned_vertices = 0;
  CHECK(ps_hierarchy_create_from_file(&hdef, mesh, &h) == PS_OK);
  if (!h) return;
  ps_sim_def def;
  ps_sim_def_init(&def);
  def.mode = PS_MODE_QUASISTATIC;
  def.pinned_vertices = left;
  def.num_pinned_vertices = 2;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  if (!sim) return;
  int32_t index = -1;
  CHECK_ERROR(ps_sim_add_handle(sim, 0, stray, 1, &index), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "group -1 of the hierarchy");
  CHECK(ps_sim_add_handle(sim, 0, right, 2, &index) == PS_OK && index == 1);
  const double offset[3] = {0.05, 0, 0};
  CHECK(ps_sim_set_handle_motion(sim, 1, NULL, NULL, NULL, 0.0, offset) == PS_OK);
  CHECK(ps_sim_step_preview(sim, 2) == PS_OK);
  double coarse_x[3 * 60];
  size_t count = 0;
  CHECK(ps_sim_get_positions(sim, 0, coarse_x, 3 * 60, &count) == PS_OK && count == 3 * 60);
  int dragged = 0; /* the coarse level keeps the corner (1, 1, 0) and drags it to x = 1.05 */
  for (int i = 0; i < 60; ++i)
    dragged += fabs(coarse_x[3 * i] - 1.05) < 1e-12 && fabs(coarse_x[3 * i + 1] - 1.0) < 1e-12;
  CHECK(dragged == 1);
  CHECK(ps_sim_refine(sim) == PS_OK);
  double fine[3 * 441];
  CHECK(ps_sim_get_positions(sim, 1, fine, 3 * 441, &count) == PS_OK && count == 3 * 441);
  CHECK(fabs(fine[3 * 440] - 1.05) < 1e-12 && fabs(fine[3 * 440 + 1] - 1.0) < 1e-12);
  CHECK(fabs(fine[3 * 420]) < 1e-12 && fabs(fine[3 * 420 + 1] - 1.0) < 1e-12);
  ps_sim_destroy(sim);
  ps_hierarchy_destroy(h);
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_capi SOURCE_DIR\n");
    return 2;
  }
  snprintf(source_dir, sizeof source_dir, "%s", argv[1]);
  test_version();
  test_threads();
  test_full_cycle();
  test_handle_reaction();
  test_misuse();
  test_parameter_listing_mode_and_lifetimes();
  test_scene_file();
  test_handle_keyframes();
  test_levels();
  test_vertex_groups();
  test_rotation_support_round_trip();
  test_progressive();
  test_crossing_input();
  test_progressive_obstacle();
  test_strain_correction();
  test_cg_refinement();
  test_extrapolation_switch();
  test_accuracy();
  test_accuracy_def();
  if (failures)
    fprintf(stderr, "%d checks failed\n", failures);
  else
    printf("all C ABI checks passed\n");
  return failures ? 1 : 0;
}
