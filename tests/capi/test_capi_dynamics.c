/*
 * A progressive animation (Progressive Dynamics) through the C ABI: a free-falling cloth on
 * three levels against the closed form of implicit Euler, frames and velocities read back,
 * initial velocities, restart, cancelling a refinement, time windows, scenes, and every
 * documented misuse.
 * Exits non-zero (printing each failed check) on failure.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "progsim.h"

#include "check.h"

enum { kCells = 8, kSide = kCells + 1, kVertices = kSide * kSide, kFaces = 2 * kCells * kCells };
static const double kStep = 0.01, kGravity = 9.81, kSpacing = 0.1;
static const int32_t kSteps = 5;

/* A kCells × kCells grid of kSpacing squares in the plane z = 0, with 16- and 36-vertex
 * coarse levels. */
static ps_hierarchy* grid_hierarchy(void) {
  double vertices[3 * kVertices];
  int32_t faces[3 * kFaces];
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      double* v = vertices + 3 * (j * kSide + i);
      v[0] = i * kSpacing;
      v[1] = j * kSpacing;
      v[2] = 0.0;
    }
  int32_t* f = faces;
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const int32_t a = j * kSide + i, b = a + 1, c = a + kSide + 1, d = a + kSide;
      const int32_t quad[6] = {a, b, c, a, c, d};
      memcpy(f, quad, sizeof quad);
      f += 6;
    }
  ps_hierarchy_def def;
  ps_hierarchy_def_init(&def);
  const int32_t coarse[2] = {16, 36};
  def.coarse_vertex_counts = coarse;
  def.num_coarse_levels = 2;
  ps_hierarchy* h = NULL;
  CHECK(ps_hierarchy_create(&def, vertices, kVertices, faces, kFaces, &h) == PS_OK);
  return h;
}

/* The defaults (a progressive animation) falling along −z, each step solved to 1e-12. */
static ps_sim* falling_cloth(const ps_hierarchy* h) {
  ps_sim_def def;
  ps_sim_def_init(&def);
  def.gravity[1] = 0.0;
  def.gravity[2] = -kGravity;
  def.solver_newton_tolerance = 1e-12;
  ps_sim* sim = NULL;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  return sim;
}

/* Implicit Euler from rest under gravity: z_n = z_0 − g h² n(n+1)/2, v_n = −g h n. */
static double fallen(int32_t n) {
  return -kGravity * kStep * kStep * n * (n + 1) / 2.0;
}

/* Every vertex of every frame of `level` and its centre of mass follow the closed form, each
 * moved along x by `vx` m/s. */
static void check_free_fall(const ps_sim* sim, int32_t level, double vx) {
  int32_t frames = 0;
  CHECK(ps_sim_num_frames(sim, level, &frames) == PS_OK && frames == kSteps + 1);
  size_t count = 0;
  CHECK(ps_sim_get_frame_positions(sim, level, 0, NULL, 0, &count) == PS_OK);
  double* rest = malloc(count * sizeof(double));
  double* x = malloc(count * sizeof(double));
  double* v = malloc(count * sizeof(double));
  CHECK(ps_sim_get_frame_positions(sim, level, 0, rest, count, &count) == PS_OK);
  double worst_x = 0.0, worst_v = 0.0;
  for (int32_t n = 0; n < frames; ++n) {
    CHECK(ps_sim_get_frame_positions(sim, level, n, x, count, &count) == PS_OK);
    CHECK(ps_sim_get_frame_velocities(sim, level, n, v, count, &count) == PS_OK);
    for (size_t i = 0; i < count; i += 3) {
      worst_x = fmax(worst_x, fabs(x[i] - rest[i] - vx * kStep * n));
      worst_x = fmax(worst_x, fabs(x[i + 2] - rest[i + 2] - fallen(n)));
      worst_v = fmax(worst_v, fabs(v[i] - vx) + fabs(v[i + 1]));
      worst_v = fmax(worst_v, fabs(v[i + 2] + kGravity * kStep * n));
    }
  }
  CHECK(worst_x < 1e-9 && worst_v < 1e-7);
  if (worst_x >= 1e-9 || worst_v >= 1e-7)
    fprintf(stderr, "level %d: position error %g m, velocity error %g m/s\n", level, worst_x,
            worst_v);
  ps_step_stats steps[kSteps];
  CHECK(ps_sim_get_step_stats(sim, level, NULL, 0, &count) == PS_OK && count == (size_t)kSteps);
  CHECK(ps_sim_get_step_stats(sim, level, steps, kSteps, &count) == PS_OK);
  for (int32_t k = 0; k < kSteps; ++k) {
    const ps_step_stats* s = &steps[k];
    CHECK(s->step == k + 1 && fabs(s->time - kStep * (k + 1)) < 1e-12 && s->converged == 1);
    CHECK(fabs(s->center_of_mass[2] - fallen(k + 1)) < 1e-9);
    CHECK(s->com_deviation < 1e-9 && s->newton_iterations >= 1 && s->seconds >= 0.0);
    CHECK(s->kinetic_energy > 0.0);
  }
  ps_dynamic_level_stats stats;
  size_t vertices = 0;
  const ps_hierarchy* h = NULL;
  CHECK(ps_sim_hierarchy(sim, &h) == PS_OK);
  CHECK(ps_hierarchy_level_size(h, level, &vertices, NULL) == PS_OK);
  CHECK(ps_sim_get_dynamic_level_stats(sim, level, &stats) == PS_OK);
  CHECK(stats.level == level && stats.vertices == (int32_t)vertices && stats.steps == kSteps);
  CHECK(stats.converged_steps == kSteps && stats.newton_iterations >= kSteps);
  free(rest);
  free(x);
  free(v);
}

typedef struct refine_log {
  int32_t reports, last_done, last_total, cancel_at;
  int phase_ok;
} refine_log;

static int32_t log_refine(void* user_data, int32_t done, int32_t total, const char* phase) {
  refine_log* log = (refine_log*)user_data;
  ++log->reports;
  log->phase_ok = log->phase_ok && strcmp(phase, "refine") == 0;
  log->last_done = done;
  log->last_total = total;
  return log->cancel_at > 0 && done >= log->cancel_at;
}

/* Preview, refine twice (the first attempt cancelled): every level falls as the closed form. */
static void test_free_fall_on_three_levels(const ps_hierarchy* h) {
  ps_sim* sim = falling_cloth(h);
  if (!sim) return;
  int32_t kind = -1, level = -1, prediction = -1;
  double weight = -1.0;
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_PROGRESSIVE_DYNAMICS);
  CHECK(ps_sim_get_prediction(sim, &prediction) == PS_OK &&
        prediction == PS_PREDICTION_VELOCITY_ONLY);
  CHECK(ps_sim_get_param(sim, "progressive.consistency_weight", &weight) == PS_OK && weight == 0);
  CHECK(ps_sim_step_preview(sim, kSteps) == PS_OK);

  refine_log log = {0, 0, 0, 2, 1};
  CHECK(ps_sim_set_progress_callback(sim, log_refine, &log) == PS_OK);
  CHECK_ERROR(ps_sim_refine(sim), PS_ERROR_CANCELLED, ps_sim_last_error(sim), "cancelled");
  CHECK(log.reports == 2 && log.last_total == kSteps && log.phase_ok);
  CHECK(ps_sim_current_level(sim, &level) == PS_OK && level == 0);
  int32_t frames = 0;
  CHECK_ERROR(ps_sim_num_frames(sim, 1, &frames), PS_ERROR_OUT_OF_RANGE, ps_sim_last_error(sim),
              "not been computed");
  log.cancel_at = 0;
  log.reports = 0;
  CHECK(ps_sim_refine(sim) == PS_OK);
  CHECK(log.reports == kSteps && log.last_done == kSteps && log.phase_ok);
  CHECK(ps_sim_set_progress_callback(sim, NULL, NULL) == PS_OK);
  CHECK(ps_sim_refine(sim) == PS_OK);
  CHECK(ps_sim_current_level(sim, &level) == PS_OK && level == 2);
  for (int32_t l = 0; l < 3; ++l) check_free_fall(sim, l, 0.0);
  CHECK_ERROR(ps_sim_refine(sim), PS_ERROR_OUT_OF_RANGE, ps_sim_last_error(sim), "finest");
  /* ps_sim_get_positions gives a level's last frame. */
  double last[3 * kVertices], frame[3 * kVertices];
  size_t count = 0;
  CHECK(ps_sim_get_positions(sim, 2, last, 3 * kVertices, &count) == PS_OK);
  CHECK(ps_sim_get_frame_positions(sim, 2, kSteps, frame, 3 * kVertices, &count) == PS_OK);
  CHECK(count == 3 * kVertices && memcmp(last, frame, sizeof last) == 0);
  ps_sim_destroy(sim);
}

/* Initial velocities carry to every level; restart starts over at rest. */
static void test_velocities_and_restart(const ps_hierarchy* h) {
  ps_sim* sim = falling_cloth(h);
  if (!sim) return;
  size_t n0 = 0;
  CHECK(ps_hierarchy_level_size(h, 0, &n0, NULL) == PS_OK && n0 == 16);
  double velocities[3 * 16] = {0};
  for (size_t i = 0; i < n0; ++i) velocities[3 * i] = 1.0;
  CHECK_ERROR(ps_sim_set_preview_velocities(sim, velocities, 3 * n0 - 1), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "47 values given");
  velocities[4] = NAN;
  CHECK_ERROR(ps_sim_set_preview_velocities(sim, velocities, 3 * n0), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "non-finite");
  velocities[4] = 0.0;
  CHECK_ERROR(ps_sim_set_preview_velocities(sim, NULL, 3), PS_ERROR_NULL_ARGUMENT,
              ps_sim_last_error(sim), "velocities");
  CHECK(ps_sim_set_preview_velocities(sim, velocities, 3 * n0) == PS_OK);
  CHECK(ps_sim_step_preview(sim, kSteps) == PS_OK);
  CHECK_ERROR(ps_sim_set_preview_velocities(sim, velocities, 3 * n0), PS_ERROR_WRONG_CALL_ORDER,
              ps_sim_last_error(sim), "restart");
  CHECK(ps_sim_refine(sim) == PS_OK);
  check_free_fall(sim, 0, 1.0);
  check_free_fall(sim, 1, 1.0);

  CHECK_ERROR(ps_sim_step_preview(sim, 1), PS_ERROR_WRONG_CALL_ORDER, ps_sim_last_error(sim),
              "restart");
  CHECK_ERROR(ps_sim_set_param(sim, "material.youngs_modulus", 2e6), PS_ERROR_WRONG_CALL_ORDER,
              ps_sim_last_error(sim), "restart");
  int32_t frames = 0, level = -1;
  CHECK(ps_sim_num_frames(sim, 0, &frames) == PS_OK && frames == kSteps + 1);
  CHECK(ps_sim_restart(sim) == PS_OK);
  CHECK(ps_sim_current_level(sim, &level) == PS_OK && level == 0);
  CHECK(ps_sim_num_frames(sim, 0, &frames) == PS_OK && frames == 1);
  CHECK_ERROR(ps_sim_num_frames(sim, 1, &frames), PS_ERROR_OUT_OF_RANGE, ps_sim_last_error(sim),
              "level 1");
  CHECK(ps_sim_set_prediction(sim, PS_PREDICTION_PROLONGED_POSITIONS) == PS_OK);
  CHECK(ps_sim_set_param(sim, "progressive.consistency_weight", 0.5) == PS_OK);
  CHECK(ps_sim_step_preview(sim, kSteps) == PS_OK);
  CHECK(ps_sim_refine(sim) == PS_OK);
  check_free_fall(sim, 1, 0.0); /* a rigid fall: every prediction and penalty agree */
  ps_sim_destroy(sim);
}

static void test_misuse(const ps_hierarchy* h) {
  ps_sim* sim = falling_cloth(h);
  if (!sim) return;
  CHECK_ERROR(ps_sim_refine(sim), PS_ERROR_WRONG_CALL_ORDER, ps_sim_last_error(sim),
              "preview at least one step");
  int32_t frames = 0, equilibrium = 0;
  size_t count = 0;
  double buffer[6];
  ps_level_stats level_stats;
  CHECK(ps_sim_num_frames(sim, 0, &frames) == PS_OK && frames == 1);
  CHECK_ERROR(ps_sim_get_frame_positions(sim, 0, 1, NULL, 0, &count), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim),
              "frame 1 of level 0 has not been computed (level 0 has 1 frame)");
  CHECK_ERROR(ps_sim_get_frame_positions(sim, 1, 0, NULL, 0, &count), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim), "level 1 has not been computed");
  CHECK_ERROR(ps_sim_get_frame_velocities(sim, 3, 0, NULL, 0, &count), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim), "level 3 does not exist");
  CHECK_ERROR(ps_sim_get_frame_positions(sim, 0, 0, buffer, 6, &count), PS_ERROR_BUFFER_TOO_SMALL,
              ps_sim_last_error(sim), "48 are needed");
  CHECK_ERROR(ps_sim_get_frame_positions(sim, 0, 0, buffer, 6, NULL), PS_ERROR_NULL_ARGUMENT,
              ps_sim_last_error(sim), "count");
  CHECK_ERROR(ps_sim_get_positions(sim, 1, NULL, 0, &count), PS_ERROR_OUT_OF_RANGE,
              ps_sim_last_error(sim), "not been computed");
  CHECK_ERROR(ps_sim_settle(sim, 5, &equilibrium), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "progressive animation");
  CHECK_ERROR(ps_sim_get_level_stats(sim, 0, &level_stats), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "progressive animation");
  CHECK_ERROR(ps_sim_set_prediction(sim, 3), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "not a ps_prediction");
  CHECK_ERROR(ps_sim_set_param(sim, "progressive.consistency_weight", -1.0),
              PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim), "consistency_weight");
  CHECK_ERROR(ps_sim_set_param(sim, "simulation.time_step", 0.02), PS_ERROR_INVALID_ARGUMENT,
              ps_sim_last_error(sim), "time step");
  CHECK_ERROR(ps_sim_set_mode(sim, PS_MODE_QUASISTATIC), PS_ERROR_INVALID_SCENE,
              ps_sim_last_error(sim), "dynamic");
  /* Nothing above changed the simulation: it still previews and refines. */
  CHECK(ps_sim_num_frames(sim, 0, &frames) == PS_OK && frames == 1);
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK && ps_sim_refine(sim) == PS_OK);
  ps_sim_destroy(sim);

  /* The animation calls on a PSQ simulation, and on a direct one. */
  ps_sim_def def;
  ps_sim_def_init(&def);
  def.mode = PS_MODE_QUASISTATIC;
  def.effects = PS_EFFECT_MEMBRANE | PS_EFFECT_BENDING;
  CHECK(ps_sim_create(h, &def, &sim) == PS_OK);
  if (!sim) return;
  int32_t kind = -1, mode = -1;
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_PSQ);
  /* PSQ does not step a dynamic scene: switching is refused and changes nothing. */
  CHECK_ERROR(ps_sim_set_mode(sim, PS_MODE_DYNAMIC), PS_ERROR_UNSUPPORTED, ps_sim_last_error(sim),
              "PSQ is quasistatic; a dynamic scene on several levels is animated");
  CHECK(ps_sim_get_mode(sim, &mode) == PS_OK && mode == PS_MODE_QUASISTATIC);
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_PSQ);
  CHECK(ps_sim_step_preview(sim, 1) == PS_OK);
  CHECK_ERROR(ps_sim_num_frames(sim, 0, &frames), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "(PSQ)");
  CHECK_ERROR(ps_sim_restart(sim), PS_ERROR_INVALID_ARGUMENT, ps_sim_last_error(sim),
              "progressive animation");
  ps_sim_destroy(sim);
  def.prediction = (ps_prediction)9;
  CHECK_ERROR(ps_sim_create(h, &def, &sim), PS_ERROR_INVALID_ARGUMENT, ps_last_error(),
              "not a ps_prediction");
}

/* A dynamic scene with coarse levels is a progressive animation; its options come through. */
/* A window of steps 2..kSteps of level 1 continues the free fall from the animation's frame
 * 2 (the coarser frame refined, velocities prolonged, at t = 2h); its frames are numbered from
 * the window's start; misuse is refused naming it. */
static void test_window(const ps_hierarchy* h) {
  ps_sim* sim = falling_cloth(h);
  if (!sim) return;
  const int32_t first = 2;
  CHECK(ps_sim_step_preview(sim, kSteps) == PS_OK);
  CHECK(ps_sim_refine_window(sim, 3, 2) == PS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(ps_sim_last_error(sim), "window of steps 3 to 2") != NULL);
  CHECK(ps_sim_refine_window(sim, 0, -1) == PS_ERROR_INVALID_ARGUMENT);
  CHECK(ps_sim_refine_window(sim, 0, kSteps + 1) == PS_ERROR_INVALID_ARGUMENT);
  CHECK(ps_sim_refine_window(sim, first, kSteps) == PS_OK);
  int32_t frames = 0;
  CHECK(ps_sim_num_frames(sim, 1, &frames) == PS_OK && frames == kSteps - first + 1);
  ps_dynamic_level_stats stats;
  CHECK(ps_sim_get_dynamic_level_stats(sim, 1, &stats) == PS_OK);
  CHECK(stats.first_step == first && stats.steps == kSteps - first);
  size_t count = 0;
  CHECK(ps_sim_get_frame_positions(sim, 1, 0, NULL, 0, &count) == PS_OK && count > 0);
  double* x = malloc(count * sizeof *x);
  double* v = malloc(count * sizeof *v);
  for (int32_t k = 0; x && v && k < frames; ++k) {
    CHECK(ps_sim_get_frame_positions(sim, 1, k, x, count, &count) == PS_OK);
    CHECK(ps_sim_get_frame_velocities(sim, 1, k, v, count, &count) == PS_OK);
    CHECK(fabs(x[2] - fallen(first + k)) < 1e-9);  /* vertex 0 started at z = 0 */
    CHECK(fabs(v[2] + kGravity * kStep * (first + k)) < 1e-8);
  }
  free(x);
  free(v);
  CHECK(ps_sim_refine(sim) == PS_ERROR_WRONG_CALL_ORDER);  /* above a window */
  CHECK(strstr(ps_sim_last_error(sim), "window") != NULL);
  ps_sim_destroy(sim);
}

static void test_scene(void) {
  const char* json =
      "{\"simulation\": {\"mode\": \"dynamic\", \"time_step\": 0.01},"
      " \"gravity\": [0, 0, -9.81], \"effects\": [\"membrane\", \"bending\", \"gravity\"],"
      " \"progressive\": {\"levels\": [12, 30], \"prediction\": \"per_frame\","
      " \"consistency_weight\": 0.25},"
      " \"bodies\": [{\"mesh\": {\"generator\": \"grid\", \"width\": 1, \"height\": 1,"
      " \"nx\": 8, \"ny\": 8}}]}";
  ps_sim* sim = NULL;
  CHECK(ps_sim_create_from_scene(json, NULL, &sim) == PS_OK);
  if (!sim) return;
  int32_t kind = -1, prediction = -1, frames = 0, levels = 0;
  double weight = 0.0;
  const ps_hierarchy* h = NULL;
  CHECK(ps_sim_get_kind(sim, &kind) == PS_OK && kind == PS_SIM_PROGRESSIVE_DYNAMICS);
  CHECK(ps_sim_get_prediction(sim, &prediction) == PS_OK && prediction == PS_PREDICTION_PER_FRAME);
  CHECK(ps_sim_get_param(sim, "progressive.consistency_weight", &weight) == PS_OK &&
        weight == 0.25);
  CHECK(ps_sim_hierarchy(sim, &h) == PS_OK && ps_hierarchy_num_levels(h, &levels) == PS_OK &&
        levels == 3);
  CHECK(ps_sim_step_preview(sim, 2) == PS_OK && ps_sim_refine(sim) == PS_OK);
  CHECK(ps_sim_num_frames(sim, 1, &frames) == PS_OK && frames == 3);
  ps_sim_destroy(sim);
}

int main(void) {
  ps_hierarchy* h = grid_hierarchy();
  if (h) {
    test_free_fall_on_three_levels(h);
    test_velocities_and_restart(h);
    test_misuse(h);
    test_window(h);
    CHECK(ps_hierarchy_destroy(h) == PS_OK);
  }
  test_scene();
  if (failures)
    fprintf(stderr, "%d checks failed\n", failures);
  else
    printf("all progressive animation checks passed\n");
  return failures ? 1 : 0;
}
