/*
 * progsim from C: load a bundled mesh, build its hierarchy, pin two corners, step a
 * preview, refine to the finest level and write the result.
 *
 *   hanging_cloth [mesh.obj] [out.obj]
 *
 * Defaults: scenes/meshes/square_cloth.obj (run from the repository root) and
 * hanging_cloth_final.obj.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "progsim.h"

/* Prints the failed call's status and message, then exits. */
static void check(int32_t status, const char* what, const char* message) {
  if (status == PS_OK) return;
  fprintf(stderr, "%s failed: %s: %s\n", what, ps_status_name(status), message);
  exit(1);
}

/* A text progress bar; returns 0 to continue. */
static int32_t print_progress(void* user_data, int32_t done, int32_t total, const char* phase) {
  (void)user_data;
  fprintf(stderr, "\r%-8s %3d/%d", phase, done, total);
  if (done == total) fputc('\n', stderr);
  return 0;
}

/* Index of the vertex nearest to (x, y, z). */
static int32_t nearest_vertex(const double* positions, size_t n, double x, double y, double z) {
  int32_t best = 0;
  double best_d2 = INFINITY;
  for (size_t i = 0; i < n; ++i) {
    const double dx = positions[3 * i] - x, dy = positions[3 * i + 1] - y,
                 dz = positions[3 * i + 2] - z;
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 < best_d2) {
      best_d2 = d2;
      best = (int32_t)i;
    }
  }
  return best;
}

int main(int argc, char** argv) {
  const char* mesh_path = argc > 1 ? argv[1] : "scenes/meshes/square_cloth.obj";
  const char* out_path = argc > 2 ? argv[2] : "hanging_cloth_final.obj";
  check(ps_check_version(PS_VERSION_HEADER), "ps_check_version", ps_last_error());
  printf("progsim %s\n", ps_version_string());

  ps_hierarchy* hierarchy = NULL;
  check(ps_hierarchy_create_from_file(NULL, mesh_path, &hierarchy), "loading the mesh",
        ps_last_error());
  int32_t levels = 0;
  size_t count = 0;
  check(ps_hierarchy_num_levels(hierarchy, &levels), "num_levels",
        ps_hierarchy_last_error(hierarchy));
  const int32_t finest = levels - 1;
  check(ps_hierarchy_get_rest_positions(hierarchy, finest, NULL, 0, &count), "size query",
        ps_hierarchy_last_error(hierarchy));
  double* rest = malloc(count * sizeof(double));
  if (!rest) return 1;
  check(ps_hierarchy_get_rest_positions(hierarchy, finest, rest, count, &count), "rest positions",
        ps_hierarchy_last_error(hierarchy));
  const size_t n = count / 3;

  ps_sim_def def;
  ps_sim_def_init(&def);
  const int32_t corners[2] = {nearest_vertex(rest, n, 0, 1, 0), nearest_vertex(rest, n, 1, 1, 0)};
  def.pinned_vertices = corners;
  def.num_pinned_vertices = 2;
  def.material_thickness = 5e-4;
  def.simulation_time_step = 0.02;
  def.gravity[1] = 0.0; /* the cloth lies in the x-y plane and swings down along −z */
  def.gravity[2] = -9.81;
  ps_sim* sim = NULL;
  check(ps_sim_create(hierarchy, &def, &sim), "ps_sim_create", ps_last_error());
  check(ps_sim_set_progress_callback(sim, print_progress, NULL), "progress",
        ps_sim_last_error(sim));
  check(ps_sim_set_param(sim, "material.youngs_modulus", 2e5), "set_param", ps_sim_last_error(sim));

  check(ps_sim_step_preview(sim, 25), "preview", ps_sim_last_error(sim));
  int32_t level = 0;
  check(ps_sim_current_level(sim, &level), "current_level", ps_sim_last_error(sim));
  while (level < finest) {
    check(ps_sim_refine(sim), "refine", ps_sim_last_error(sim));
    check(ps_sim_current_level(sim, &level), "current_level", ps_sim_last_error(sim));
  }
  check(ps_sim_step_preview(sim, 25), "finest-level steps", ps_sim_last_error(sim));

  double* x = malloc(count * sizeof(double));
  if (!x) return 1;
  check(ps_sim_get_positions(sim, finest, x, count, &count), "positions", ps_sim_last_error(sim));
  double lowest = INFINITY;
  for (size_t i = 0; i < n; ++i) lowest = fmin(lowest, x[3 * i + 2]);
  ps_level_stats stats;
  check(ps_sim_get_level_stats(sim, finest, &stats), "stats", ps_sim_last_error(sim));
  printf("level %d: %d steps, %d Newton iterations, %.3f s, lowest point z = %.3f m\n", stats.level,
         stats.steps, stats.newton_iterations, stats.seconds, lowest);
  check(ps_sim_write_mesh(sim, finest, out_path), "write_mesh", ps_sim_last_error(sim));
  printf("wrote %s\n", out_path);

  free(x);
  free(rest);
  ps_sim_destroy(sim);
  ps_hierarchy_destroy(hierarchy);
  return 0;
}
