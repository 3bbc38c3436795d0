/*
 * Solids through the C ABI (VPD, issue 32 §7): a tet hierarchy from a tet mesh and from a closed
 * surface, its levels' tets and boundary faces, prolongation of affine maps, a VPD animation
 * and a direct simulation falling freely against the closed form of implicit Euler, solid
 * scenes with and without coarse levels, and every documented misuse. Exits non-zero (printing each
 * failed check) on failure.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "progsim.h"

enum { kCells = 3, kSide = kCells + 1, kVertices = kSide * kSide * kSide };
enum { kTets = 6 * kCells * kCells * kCells, kBoundaryVertices = kVertices - 8 };
static const double kSpacing = 0.1, kStep = 0.01, kGravity = 9.81;
static const int32_t kSteps = 4;

static double g_vertices[3 * kVertices];
static int32_t g_tets[4 * kTets];

/* Signed volume of the tet (a, b, c, d) of `v`, m³. */
static double tet_volume(const double* v, const int32_t* t) {
  double e[3][3];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) e[k][i] = v[3 * t[k + 1] + i] - v[3 * t[0] + i];
  return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
          e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
          e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6.0;
}

/* A kCells³ grid of kSpacing cubes, each split into the six tets of its main diagonal (Kuhn),
 * all positively oriented. */
static void make_tet_box(void) {
  for (int k = 0; k < kSide; ++k)
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        double* v = g_vertices + 3 * ((k * kSide + j) * kSide + i);
        v[0] = i * kSpacing;
        v[1] = j * kSpacing;
        v[2] = k * kSpacing;
      }
  static const int axes[6][2] = {{1, 2}, {1, 4}, {2, 1}, {2, 4}, {4, 1}, {4, 2}};
  int32_t* t = g_tets;
  for (int k = 0; k < kCells; ++k)
    for (int j = 0; j < kCells; ++j)
      for (int i = 0; i < kCells; ++i) {
        int32_t corner[8];
        for (int c = 0; c < 8; ++c)
          corner[c] = ((k + (c >> 2 & 1)) * kSide + j + (c >> 1 & 1)) * kSide + i + (c & 1);
        for (int p = 0; p < 6; ++p) {
          t[0] = corner[0];
          t[1] = corner[axes[p][0]];
          t[2] = corner[axes[p][0] | axes[p][1]];
          t[3] = corner[7];
          if (tet_volume(g_vertices, t) < 0.0) {
            const int32_t swap = t[1];
            t[1] = t[2];
            t[2] = swap;
          }
          t += 4;
        }
      }
}

/* The box with one coarse level of 20 boundary vertices, counting its progress calls. */
static int g_progress_calls = 0;
static int32_t count_progress(void* user, int32_t done, int32_t total, const char* phase) {
  (void)user;
  CHECK(done >= 0 && done <= total && phase != NULL);
  ++g_progress_calls;
  return 0;
}

static ps_hierarchy* box_hierarchy(void) {
  ps_hierarchy_def def;
  ps_hierarchy_def_init(&def);
  CHECK(def.tet_size_factor == 0.6 && def.tet_cell_size == 0.0);
  const int32_t coarse[1] = {20};
  def.coarse_vertex_counts = coarse;
  def.num_coarse_levels = 1;
  def.progress = count_progress;
  ps_hierarchy* h = NULL;
  CHECK(ps_hierarchy_create_solid(&def, g_vertices, kVertices, g_tets, kTets, &h) == PS_OK);
  CHECK(g_progress_calls > 0);
  return h;
}

/* Levels, their tets and boundary faces, and the prolongation of an affine map. */
static void test_levels(const ps_hierarchy* h) {
  int32_t levels = 0, solid = 0;
  CHECK(ps_hierarchy_num_levels(h, &levels) == PS_OK && levels == 2);
  CHECK(ps_hierarchy_is_solid(h, &solid) == PS_OK && solid == 1);
  size_t n = 0, faces = 0, count = 0;
  CHECK(ps_hierarchy_level_size(h, 1, &n, &faces) == PS_OK && n == kVertices);
  CHECK(faces == 2 * 6 * kCells * kCells); /* two triangles per boundary square */
  CHECK(ps_hierarchy_get_tets(h, 1, NULL, 0, &count) == PS_OK && count == 4 * kTets);
  int32_t* tets = malloc(count * sizeof(int32_t));
  CHECK(ps_hierarchy_get_tets(h, 1, tets, count, &count) == PS_OK);
  CHECK(memcmp(tets, g_tets, sizeof g_tets) == 0); /* the finest level is the input */
  free(tets);
  CHECK(ps_hierarchy_level_size(h, 0, &n, &faces) == PS_OK && n >= 20);
  CHECK(ps_hierarchy_get_tets(h, 0, NULL, 0, &count) == PS_OK && count % 4 == 0 && count > 0);
  tets = malloc(count * sizeof(int32_t));
  double* x = malloc(3 * n * sizeof(double));
  CHECK(ps_hierarchy_get_tets(h, 0, tets, count, &count) == PS_OK);
  CHECK(ps_hierarchy_get_rest_positions(h, 0, x, 3 * n, &count) == PS_OK && count == 3 * n);
  double volume = 0.0;
  int inverted = 0;
  size_t num_tets = 0;
  CHECK(ps_hierarchy_get_tets(h, 0, NULL, 0, &num_tets) == PS_OK);
  for (size_t t = 0; t < num_tets / 4; ++t) {
    for (int c = 0; c < 4; ++c) CHECK(tets[4 * t + c] >= 0 && (size_t)tets[4 * t + c] < n);
    const double vt = tet_volume(x, tets + 4 * t);
    inverted += vt <= 0.0;
    volume += vt;
  }
  CHECK(inverted == 0);
  /* a decimated and re-tetrahedralized box of 0.027 m³: within 20 % */
  CHECK(volume > 0.8 * 0.027 && volume <= 0.027 * (1 + 1e-9));
  /* x ↦ A x + b on level 0 prolongs to A x + b on the finest (W reproduces affine maps) */
  static const double a[3][3] = {{1.1, 0.2, 0.0}, {-0.1, 0.9, 0.3}, {0.05, 0.0, 1.2}};
  static const double b[3] = {0.5, -0.2, 1.0};
  double* y = malloc(3 * n * sizeof(double));
  for (size_t v = 0; v < n; ++v)
    for (int i = 0; i < 3; ++i)
      y[3 * v + i] = b[i] + a[i][0] * x[3 * v] + a[i][1] * x[3 * v + 1] + a[i][2] * x[3 * v + 2];
  double fine[3 * kVertices];
  CHECK(ps_hierarchy_prolong(h, 0, y, 3 * n, fine, 3 * kVertices, &count) == PS_OK);
  double worst = 0.0;
  for (int v = 0; v < kVertices; ++v)
    for (int i = 0; i < 3; ++i) {
      const double* p = g_vertices + 3 * v;
      const double exact = b[i] + a[i][0] * p[0] + a[i][1] * p[1] + a[i][2] * p[2];
      worst = fmax(worst, fabs(fine[3 * v + i] - exact));
    }
  CHECK(worst < 1e-12);
  free(tets);
  free(x);
  free(y);
}

/* Implicit Euler from rest at a uniform acceleration a along −z: z_n = z_0 − a h² n(n+1)/2. */
static double fallen(double a, int32_t n) {
  return -a * kStep * kStep * n * (n + 1) / 2.0;
}

/* A refined level at its own acceleration a along −z whose steps take the coarser level's
 * velocity (VPD's velocity-only prediction, x̂ = xᵗ + h U v_cᵗ) when the coarser level fell at
 * a_c: z_n − z_0 = −h² (a_c n(n−1)/2 + a n). With a_c = a this is fallen(a, n). */
static double fallen_after(double a_coarse, double a, int32_t n) {
  return -kStep * kStep * (a_coarse * n * (n - 1) / 2.0 + a * n);
}

/* Every vertex of every frame of `level` follows the closed form at acceleration `a` along −z (a
 * free solid under a uniform acceleration stays rigid), its steps predicted from a coarser
 * level that fell at `a_coarse` (a for the preview). */
static void check_uniform_fall(const ps_sim* sim, int32_t level, double a_coarse, double a) {
  int32_t frames = 0;
  CHECK(ps_sim_num_frames(sim, level, &frames) == PS_OK && frames == kSteps + 1);
  size_t count = 0;
  CHECK(ps_sim_get_frame_positions(sim, level, 0, NULL, 0, &count) == PS_OK && count > 0);
  double* rest = malloc(count * sizeof(double));
  double* x = malloc(count * sizeof(double));
  CHECK(ps_sim_get_frame_positions(sim, level, 0, rest, count, &count) == PS_OK);
  double worst = 0.0;
  for (int32_t f = 0; f < frames; ++f) {
    CHECK(ps_sim_get_frame_positions(sim, level, f, x, count, &count) == PS_OK);
    for (size_t v = 0; v < count / 3; ++v) {
      worst = fmax(worst, fabs(x[3 * v] - rest[3 * v]) + fabs(x[3 * v + 1] - rest[3 * v + 1]));
      worst = fmax(worst, fabs(x[3 * v + 2] - rest[3 * v + 2] - fallen_after(a_coarse, a, f)));
    }
  }
  if (worst > 1e-8) fprintf(stderr, "level %d: free fall off by %g m\n", (int)level, worst);
  CHECK(worst < 1e-8);
  free(rest);
  free(x);
}

static void check_free_fall(const ps_sim* sim, int32_t level) {
  check_uniform_fall(sim, level, kGravity, kGravity);
}

/* A solid's simulation def: elasticity and gravity along −z. */
static ps_sim_def falling_def(void) {
  ps_sim_def def;
  ps_sim_def_init(&def);
  def.effects = PS_EFFECT_ELASTICITY | PS_EFFECT_GRAVITY;
  def.gravity[1] = 0.0;
  def.gravity[2] = -kGravity;
  return def;
}

/* VPD on the box: kind, preview and refinement in free fall, stats. */
static void test_animation(const ps_hierarchy* h) {
  ps_sim_def def = falling_def();
  def.solver_newton_tolerance = 1e-12;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  int32_t kind = -1, level = -1;
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_VOLUMETRIC_DYNAMICS);
  CHECK(ps_sim_step_preview(sim, kSteps) == PS_OK);
  CHECK(ps_sim_refine(sim) == PS_OK);
  CHECK(ps_sim_current_level(sim, &level) == PS_OK && level == 1);
  check_free_fall(sim, 0);
  check_free_fall(sim, 1);
  ps_dynamic_level_stats stats;
  CHECK(ps_sim_get_dynamic_level_stats(sim, 1, &stats) == PS_OK);
  CHECK(stats.vertices == kVertices && stats.steps == kSteps && stats.converged_steps == kSteps);
  CHECK_ERROR(ps_sim_refine(sim), PS_ERROR_OUT_OF_RANGE, ps_sim_last_error(sim), "finest");
  CHECK_ERROR(ps_hierarchy_destroy((ps_hierarchy*)h), PS_ERROR_WRONG_CALL_ORDER, ps_last_error(),
              "destroy them first");
  CHECK(ps_sim_restart(sim) == PS_OK);
  CHECK(ps_sim_current_level(sim, &level) == PS_OK && level == 0);
  ps_sim_destroy(sim);
  /* a NULL def: elasticity and gravity, animated */
  CHECK(ps_sim_create(h, NULL, &sim) == PS_OK);
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_VOLUMETRIC_DYNAMICS);
  uint32_t effects = 0;
  CHECK(ps_sim_get_effects(sim, &effects) == PS_OK &&
        effects == (PS_EFFECT_ELASTICITY | PS_EFFECT_GRAVITY));
  ps_sim_destroy(sim);
}

/* A closed surface (the unit cube's 12 triangles) filled with tets keeps its volume. */
static void test_closed_surface(void) {
  static const double cube[8 * 3] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                     0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  static const int32_t faces[12 * 3] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                        1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  ps_hierarchy_def def;
  ps_hierarchy_def_init(&def);
  def.tet_cell_size = 0.4;
  ps_hierarchy* h = NULL;
  CHECK(ps_hierarchy_create_solid_from_surface(&def, cube, 8, faces, 12, &h) == PS_OK);
  size_t n = 0, count = 0;
  CHECK(ps_hierarchy_level_size(h, 0, &n, NULL) == PS_OK && n >= 8);
  double* x = malloc(3 * n * sizeof(double));
  CHECK(ps_hierarchy_get_rest_positions(h, 0, x, 3 * n, &count) == PS_OK);
  CHECK(ps_hierarchy_get_tets(h, 0, NULL, 0, &count) == PS_OK && count > 0);
  int32_t* tets = malloc(count * sizeof(int32_t));
  CHECK(ps_hierarchy_get_tets(h, 0, tets, count, &count) == PS_OK);
  double volume = 0.0;
  for (size_t t = 0; t < count / 4; ++t) volume += tet_volume(x, tets + 4 * t);
  CHECK(fabs(volume - 1.0) < 1e-12);
  free(x);
  free(tets);
  CHECK(ps_hierarchy_destroy(h) == PS_OK);
  /* an open surface (one face dropped) cannot be filled */
  CHECK_ERROR(ps_hierarchy_create_solid_from_surface(&def, cube, 8, faces, 11, &h),
              PS_ERROR_INVALID_MESH, ps_last_error(), "closed");
  def.tet_cell_size = NAN;
  CHECK_ERROR(ps_hierarchy_create_solid_from_surface(&def, cube, 8, faces, 12, &h),
              PS_ERROR_INVALID_ARGUMENT, ps_last_error(), "tet_cell_size");
}

/* A handle by box on VPD: each level holds its own vertices at x = 0 in place on every frame. */
static void test_box_handle(const ps_hierarchy* h) {
  ps_sim_def def = falling_def();
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  const double lo[3] = {-0.01, -1.0, -1.0}, hi[3] = {0.01, 1.0, 1.0};
  const double inverted[3] = {0.02, 1.0, 1.0}, far[3] = {5.0, 5.0, 5.0}, farther[3] = {6, 6, 6};
  int32_t index = -1;
  CHECK_ERROR(ps_sim_add_handle_box(sim, 0, inverted, hi, &index), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "box_min.x");
  CHECK_ERROR(ps_sim_add_handle_box(sim, 0, far, farther, &index), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "holds no vertex");
  CHECK_ERROR(ps_sim_add_handle_box(sim, 1, lo, hi, &index), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "body 1");
  CHECK(ps_sim_add_handle_box(sim, 0, lo, hi, &index) == PS_OK && index == 0);
  CHECK(ps_sim_step_preview(sim, kSteps) == PS_OK && ps_sim_refine(sim) == PS_OK);
  for (int32_t level = 0; level < 2; ++level) {
    size_t n = 0, count = 0;
    CHECK(ps_hierarchy_level_size(h, level, &n, NULL) == PS_OK);
    double* rest = malloc(3 * n * sizeof(double));
    double* x = malloc(3 * n * sizeof(double));
    CHECK(ps_hierarchy_get_rest_positions(h, level, rest, 3 * n, &count) == PS_OK);
    CHECK(ps_sim_get_frame_positions(sim, level, kSteps, x, 3 * n, &count) == PS_OK);
    int held = 0;
    double held_moved = 0.0, free_drop = 0.0;
    for (size_t v = 0; v < n; ++v) {
      const double drop = rest[3 * v + 2] - x[3 * v + 2];
      if (fabs(rest[3 * v]) <= 0.01) {
        ++held;
        held_moved = fmax(held_moved, fabs(drop) + fabs(x[3 * v] - rest[3 * v]));
      } else {
        free_drop = fmax(free_drop, drop);
      }
    }
    CHECK(held >= 4 && held_moved == 0.0 && free_drop > 0.0);
    free(rest);
    free(x);
  }
  ps_sim_destroy(sim);
}

/* The volume of hierarchy level `level` from its own tets, m³. */
static double level_volume(const ps_hierarchy* h, int32_t level) {
  size_t n = 0, count = 0, tet_count = 0;
  CHECK(ps_hierarchy_level_size(h, level, &n, NULL) == PS_OK);
  CHECK(ps_hierarchy_get_tets(h, level, NULL, 0, &tet_count) == PS_OK && tet_count > 0);
  double* rest = malloc(3 * n * sizeof(double));
  int32_t* tets = malloc(tet_count * sizeof(int32_t));
  CHECK(ps_hierarchy_get_rest_positions(h, level, rest, 3 * n, &count) == PS_OK);
  CHECK(ps_hierarchy_get_tets(h, level, tets, tet_count, &tet_count) == PS_OK);
  double volume = 0.0;
  for (size_t t = 0; t < tet_count / 4; ++t) volume += tet_volume(rest, tets + 4 * t);
  free(rest);
  free(tets);
  return volume;
}

/* A load by box on VPD levels, which share no vertices: a box around the whole solid with a
 * total force F spread by mass accelerates every level's vertices at F / (ρ V_l), V_l the level's
 * own volume (the coarse level's is not the finest's), without gravity; misuse of the box is
 * named. */
static void test_box_load(const ps_hierarchy* h) {
  ps_sim_def def = falling_def();
  def.effects = PS_EFFECT_ELASTICITY;
  def.solver_newton_tolerance = 1e-12;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  const double lo[3] = {-1.0, -1.0, -1.0}, hi[3] = {1.0, 1.0, 1.0};
  const double far[3] = {5.0, 5.0, 5.0}, farther[3] = {6.0, 6.0, 6.0};
  const double force = 3.0; /* N along −z */
  ps_load_def load;
  ps_load_def_init(&load);
  CHECK(load.box_min == NULL && load.box_max == NULL);
  load.force[2] = -force;
  load.box_min = lo;
  int32_t index = -1;
  CHECK_ERROR(ps_sim_add_load(sim, &load, &index), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "both corners");
  const int32_t some[1] = {0};
  load.box_max = hi;
  load.vertices = some;
  load.num_vertices = 1;
  CHECK_ERROR(ps_sim_add_load(sim, &load, &index), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "not both");
  load.vertices = NULL;
  load.num_vertices = 0;
  load.box_min = far;
  load.box_max = farther;
  CHECK_ERROR(ps_sim_add_load(sim, &load, &index), PS_ERROR_INVALID_SCENE, ps_sim_last_error(sim),
              "holds no vertex");
  load.box_min = lo;
  load.box_max = hi;
  CHECK(ps_sim_add_load(sim, &load, &index) == PS_OK && index == 0);
  CHECK(ps_sim_step_preview(sim, kSteps) == PS_OK && ps_sim_refine(sim) == PS_OK);
  const double a0 = force / (def.material_density * level_volume(h, 0));
  const double a1 = force / (def.material_density * level_volume(h, 1));
  CHECK(fabs(a1 / a0 - 1.0) > 1e-3); /* else the prediction rule is not tested */
  check_uniform_fall(sim, 0, a0, a0);
  check_uniform_fall(sim, 1, a0, a1);
  ps_sim_destroy(sim);
}

/* Bad tet meshes, calls that apply to shells only, and solids' scenes that cannot be run. */
static void test_misuse(const ps_hierarchy* h) {
  ps_hierarchy* bad = NULL;
  int32_t tets[4 * kTets];
  memcpy(tets, g_tets, sizeof tets);
  tets[5] = kVertices; /* out of range */
  CHECK_ERROR(ps_hierarchy_create_solid(NULL, g_vertices, kVertices, tets, kTets, &bad),
              PS_ERROR_INVALID_MESH, ps_last_error(), "");
  memcpy(tets, g_tets, sizeof tets);
  const int32_t swap = tets[1]; /* inverted */
  tets[1] = tets[2];
  tets[2] = swap;
  CHECK_ERROR(ps_hierarchy_create_solid(NULL, g_vertices, kVertices, tets, kTets, &bad),
              PS_ERROR_INVALID_MESH, ps_last_error(), "");
  CHECK_ERROR(ps_hierarchy_create_solid(NULL, NULL, kVertices, g_tets, kTets, &bad),
              PS_ERROR_NULL_ARGUMENT, ps_last_error(), "vertices");
  CHECK_ERROR(ps_hierarchy_create_solid(NULL, g_vertices, kVertices, g_tets, 0, &bad),
              PS_ERROR_INVALID_MESH, ps_last_error(), "tets");
  CHECK_ERROR(ps_hierarchy_create_solid_from_file(NULL, "no/such/file.mesh", &bad), PS_ERROR_IO,
              ps_last_error(), "no/such/file.mesh");
  CHECK(bad == NULL);
  ps_hierarchy_def def;
  ps_hierarchy_def_init(&def);
  def.tet_size_factor = -1.0;
  const int32_t coarse[1] = {20};
  def.coarse_vertex_counts = coarse;
  def.num_coarse_levels = 1;
  CHECK_ERROR(ps_hierarchy_create_solid(&def, g_vertices, kVertices, g_tets, kTets, &bad),
              PS_ERROR_INVALID_ARGUMENT, ps_last_error(), "size_factor");
  int32_t batches = 0;
  CHECK_ERROR(ps_hierarchy_save(h, "unused.psh"), PS_ERROR_UNSUPPORTED, ps_hierarchy_last_error(h),
              "solid");
  CHECK_ERROR(ps_hierarchy_num_expansion_batches(h, 0, &batches), PS_ERROR_UNSUPPORTED,
              ps_hierarchy_last_error(h), "solid");
  size_t count = 0;
  CHECK_ERROR(ps_hierarchy_get_tets(h, 2, NULL, 0, &count), PS_ERROR_OUT_OF_RANGE,
              ps_hierarchy_last_error(h), "level 2");
  ps_sim_def sim_def;
  ps_sim_def_init(&sim_def); /* a cloth's effects on a solid */
  ps_sim* sim = NULL;
  CHECK_ERROR(ps_sim_create(h, &sim_def, &sim), PS_ERROR_INVALID_SCENE, ps_last_error(),
              "membrane");
  sim_def.effects = PS_EFFECT_ELASTICITY;
  sim_def.mode = PS_MODE_QUASISTATIC;
  CHECK_ERROR(ps_sim_create(h, &sim_def, &sim), PS_ERROR_UNSUPPORTED, ps_last_error(),
              "quasistatic");
  CHECK(sim == NULL);
}

/* One level: a direct simulation of the solid, falling as implicit Euler does; a scene without
 * coarse levels is one too, on a one-level solid hierarchy it owns. */
static void test_direct(void) {
  ps_hierarchy* h = NULL;
  CHECK(ps_hierarchy_create_solid(NULL, g_vertices, kVertices, g_tets, kTets, &h) == PS_OK);
  ps_sim_def def = falling_def();
  def.solver_newton_tolerance = 1e-12;
  ps_sim* sim = NULL;
  int32_t kind = -1;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_DIRECT);
  CHECK(ps_sim_step_preview(sim, kSteps) == PS_OK);
  double x[3 * kVertices];
  size_t count = 0;
  CHECK(ps_sim_get_positions(sim, 0, x, 3 * kVertices, &count) == PS_OK && count == 3 * kVertices);
  double worst = 0.0;
  for (int v = 0; v < kVertices; ++v)
    worst = fmax(worst, fabs(x[3 * v + 2] - g_vertices[3 * v + 2] - fallen(kGravity, kSteps)));
  CHECK(worst < 1e-8);
  ps_sim_destroy(sim);
  CHECK(ps_hierarchy_destroy(h) == PS_OK);
  const char* json =
      "{\"effects\": [\"elasticity\", \"gravity\"],"
      " \"simulation\": {\"mode\": \"dynamic\", \"time_step\": 0.01, \"duration\": 0.03},"
      " \"bodies\": [{\"name\": \"jelly\", \"mesh\": {\"generator\": \"tet_box\","
      " \"size\": [0.3, 0.3, 0.3], \"cells\": [3, 3, 3]}}]}";
  CHECK(ps_sim_create_from_scene(json, NULL, &sim) == PS_OK);
  const ps_hierarchy* owned = NULL;
  int32_t solid = 0, levels = 0;
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_DIRECT);
  CHECK(ps_sim_hierarchy(sim, &owned) == PS_OK);
  CHECK(ps_hierarchy_is_solid(owned, &solid) == PS_OK && solid == 1);
  CHECK(ps_hierarchy_num_levels(owned, &levels) == PS_OK && levels == 1);
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  ps_sim_destroy(sim);
}

/* A dynamic scene with a volumetric body and coarse levels is VPD on a solid's hierarchy. */
static void test_scene(void) {
  const char* json =
      "{\"name\": \"jelly\", \"effects\": [\"elasticity\", \"gravity\"],"
      " \"simulation\": {\"mode\": \"dynamic\", \"time_step\": 0.01, \"duration\": 0.03},"
      " \"progressive\": {\"levels\": [20]},"
      " \"bodies\": [{\"name\": \"jelly\", \"mesh\": {\"generator\": \"tet_box\","
      " \"size\": [0.3, 0.3, 0.3], \"cells\": [3, 3, 3]}}]}";
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene(json, NULL, &sim) == PS_OK);
  int32_t kind = -1, solid = 0, levels = 0;
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_VOLUMETRIC_DYNAMICS);
  const ps_hierarchy* h = NULL;
  CHECK(ps_sim_hierarchy(sim, &h) == PS_OK);
  CHECK(ps_hierarchy_is_solid(h, &solid) == PS_OK && solid == 1);
  CHECK(ps_hierarchy_num_levels(h, &levels) == PS_OK && levels == 2);
  CHECK(ps_sim_step_preview(sim, 3) == PS_OK && ps_sim_refine(sim) == PS_OK);
  int32_t frames = 0;
  CHECK(ps_sim_num_frames(sim, 1, &frames) == PS_OK && frames == 4);
  CHECK(ps_sim_set_param(sim, "material.youngs_modulus", 2e5) == PS_ERROR_WRONG_CALL_ORDER);
  CHECK(ps_sim_restart(sim) == PS_OK);
  CHECK(ps_sim_set_param(sim, "material.youngs_modulus", 2e5) == PS_OK);
  ps_sim_destroy(sim);
}

/* A scene that mixes a shell and a solid runs directly; on several levels it is refused by name. */
static void test_mixed_scene(void) {
  const char* mixed =
      "{\"effects\": [\"membrane\", \"bending\", \"elasticity\", \"gravity\", \"contact\"],"
      " \"simulation\": {\"mode\": \"dynamic\", \"time_step\": 0.01, \"duration\": 0.03},"
      " \"bodies\": [{\"name\": \"jelly\", \"mesh\": {\"generator\": \"tet_box\","
      " \"size\": [0.3, 0.3, 0.3], \"cells\": [2, 2, 2]}},"
      " {\"name\": \"cloth\", \"mesh\": {\"generator\": \"grid\", \"width\": 0.4,"
      " \"height\": 0.4, \"nx\": 4, \"ny\": 4}, \"transform\": {\"rotate\": {\"axis\": [1, 0, 0], "
      "\"degrees\": -90},"
      " \"translate\": [-0.2, 0.2, 0.2]}}]";
  char json[1024];
  snprintf(json, sizeof json, "%s}", mixed);
  ps_sim* sim = NULL;
  int32_t kind = -1;
  CHECK(ps_sim_create_from_scene(json, NULL, &sim) == PS_OK);
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_DIRECT);
  CHECK(ps_sim_step_preview(sim, 2) == PS_OK);
  enum { kMixedVertices = 27 + 25 };  // the jelly's 3³ tet vertices, then the cloth's 5²
  double x[3 * kMixedVertices];
  size_t count = 0;
  CHECK(ps_sim_get_positions(sim, 0, x, 3 * kMixedVertices, &count) == PS_OK &&
        count == 3 * kMixedVertices);
  CHECK(x[3 * 27 + 1] < 0.2 && x[3 * 27 + 1] > 0.15);  // the cloth falls along −y (the default)
  ps_sim_destroy(sim);
  snprintf(json, sizeof json, "%s, \"progressive\": {\"levels\": [20]}}", mixed);
  sim = NULL;
  CHECK_ERROR(ps_sim_create_from_scene(json, NULL, &sim), PS_ERROR_UNSUPPORTED, ps_last_error(),
              "mixes shells and volumetric");
  CHECK(sim == NULL);
}

int main(void) {
  make_tet_box();
  ps_hierarchy* h = box_hierarchy();
  if (h) {
    test_levels(h);
    test_animation(h);
    test_box_handle(h);
    test_box_load(h);
    test_misuse(h);
    CHECK(ps_hierarchy_destroy(h) == PS_OK);
  }
  test_closed_surface();
  test_direct();
  test_scene();
  test_mixed_scene();
  if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
