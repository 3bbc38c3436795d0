#pragma once
/// @file `progsim hierarchy`: builds a mesh hierarchy from a mesh file and saves it.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace progsim::cli {

/// Options of `progsim hierarchy MESH --out FILE (--levels N,... | --ratio R --count K)`.
struct HierarchyCommand {
  std::string mesh_path;
  std::string out_path;
  std::vector<int> levels;
  double ratio = 0.0;
  int count = 0;
  double offset = 0.0;  ///< contact offset ξ of every vertex (m): 0 checks crossings only
  bool quiet = false;
};

/// Registers the subcommand on app; options are written into `options` when parsed.
CLI::App* add_hierarchy_command(CLI::App& app, HierarchyCommand& options);

/// Builds, saves and summarises the hierarchy (stdout): per level its size, expansion batches
/// and crossing face pairs (CGAL's exact check). Throws progsim::Error on bad input.
int run_hierarchy_command(const HierarchyCommand& options);

}  // namespace progsim::cli
