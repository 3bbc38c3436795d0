#pragma once
/// @file Where the tests find real meshes nobody here wrote (DESIGN.md §4): CGAL's data set,
/// fetched by scripts/fetch_test_meshes.sh into $PROGSIM_MESH_CACHE (default
/// $HOME/.cache/progsim/meshes).
#include <cstdlib>
#include <filesystem>
#include <string>

#include "mesh/mesh_io.hpp"

namespace progsim::test_support {

/// The folder holding CGAL's meshes (*.off).
inline std::filesystem::path real_mesh_folder() {
  const char* cache = std::getenv("PROGSIM_MESH_CACHE");
  const char* home = std::getenv("HOME");
  const std::filesystem::path root =
      cache && *cache ? std::filesystem::path(cache)
                      : std::filesystem::path(home ? home : "") / ".cache/progsim/meshes";
  return root / "meshes";
}

/// The mesh `file` of that folder, read (Error(io_error) if it is missing).
inline TriangleMesh real_mesh(const std::string& file) {
  return read_mesh((real_mesh_folder() / file).string());
}

}  // namespace progsim::test_support
