#include "cli/hierarchy_command.hpp"

#include <cstdio>

#include "cli/progress_bar.hpp"
#include "common/error.hpp"
#include "common/timer.hpp"
#include "hierarchy/hierarchy_io.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/intersection_check.hpp"
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
  cmd->add_option("--offset", options.offset,
                  "contact offset of every vertex in m (half the shell thickness): no level "
                  "brings a vertex and a face, or two edges, within twice this")
      ->check(CLI::NonNegativeNumber);
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
  if (options.offset > 0.0) build.contact_offsets.assign(mesh.num_vertices(), options.offset);
  ProgressBar bar("hierarchy", 100);
  const Timer timer;
  const MeshHierarchy hierarchy =
      build_hierarchy(mesh, build, options.quiet ? nullptr : draw_percent, &bar);
  const double seconds = timer.seconds();
  if (!options.quiet) bar.finish();
  save_hierarchy(hierarchy, options.out_path);
  std::printf("level  vertices  faces  expansion batches  crossing face pairs\n");
  for (int l = 0; l < hierarchy.num_levels(); ++l) {
    const TriangleMesh& level = hierarchy.levels[l].rest;
    std::printf("%5d  %8d  %5d  %17s  %19zu\n", l, level.num_vertices(), level.num_faces(),
                l < hierarchy.finest()
                    ? std::to_string(hierarchy.expansion_batches[l].size()).c_str()
                    : "-",
                intersecting_faces(level.vertices, level.faces).size());
  }
  std::printf("built in %.2f s; saved %s\n", seconds, options.out_path.c_str());
  return 0;
}

}  // namespace progsim::cli
