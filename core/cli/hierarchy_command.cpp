#include "cli/hierarchy_command.hpp"

#include <cstdio>

#include "cli/progress_bar.hpp"
#include "common/error.hpp"
#include "common/timer.hpp"
#include "hierarchy/hierarchy_io.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/mesh_io.hpp"

namespace progsim::cli {

CLI::App* add_hierarchy_command(CLI::App& app, HierarchyCommand& options) {
  CLI::App* cmd = app.add_subcommand(
      "hierarchy", "decimate a mesh into levels (PSQ §4.1) and save the hierarchy for scenes");
  cmd->add_option("mesh", options.mesh_path, "input mesh (OBJ, OFF or PLY)")->required();
  cmd->add_option("--out", options.out_path, "hierarchy file to write")->required();
  auto* levels = cmd->add_option("--levels", options.levels,
                                 "vertex counts of the coarse levels, e.g. 500,2000")
                     ->delimiter(',');
  auto* ratio = cmd->add_option("--ratio", options.ratio, "vertex ratio between levels (> 1)");
  auto* count = cmd->add_option("--count", options.count, "number of coarse levels");
  ratio->needs(count)->excludes(levels);
  count->needs(ratio)->excludes(levels);
  cmd->add_flag("--quiet", options.quiet, "no progress bar");
  return cmd;
}

int run_hierarchy_command(const HierarchyCommand& options) {
  const TriangleMesh mesh = read_mesh(options.mesh_path);
  HierarchyOptions build;
  const bool by_ratio = options.ratio != 0.0 || options.count != 0;
  build.coarse_vertex_counts =
      by_ratio ? geometric_level_counts(mesh.num_vertices(), options.ratio, options.count)
               : options.levels;
  if (build.coarse_vertex_counts.empty())
    fail(Status::invalid_argument, "hierarchy: give --levels or --ratio with --count");
  ProgressBar bar("hierarchy", 100);
  const Timer timer;
  const MeshHierarchy hierarchy =
      build_hierarchy(mesh, build, options.quiet ? nullptr : draw_percent, &bar);
  const double seconds = timer.seconds();
  if (!options.quiet) bar.finish();
  save_hierarchy(hierarchy, options.out_path);
  std::printf("level  vertices  faces  expansion batches\n");
  for (int l = 0; l < hierarchy.num_levels(); ++l)
    std::printf("%5d  %8d  %5d  %s\n", l, hierarchy.levels[l].rest.num_vertices(),
                hierarchy.levels[l].rest.num_faces(),
                l < hierarchy.finest()
                    ? std::to_string(hierarchy.expansion_batches[l].size()).c_str()
                    : "-");
  std::printf("built in %.2f s; saved %s\n", seconds, options.out_path.c_str());
  return 0;
}

}  // namespace progsim::cli
