#include "hierarchy/level_prolongation.hpp"

#include <string>

#include "common/error.hpp"

namespace progsim {
namespace {

const TriangleMesh& coarse_level(const MeshHierarchy& h, int level) {
  if (level < 0 || level >= h.finest())
    fail(Status::out_of_range, "hierarchy: level " + std::to_string(level) +
                                   " has no prolongation (coarse levels are 0 to " +
                                   std::to_string(h.finest() - 1) + ")");
  return h.levels[level].rest;
}

}  // namespace

ShellProlongation direct_prolongation(const MeshHierarchy& h, int level) {
  const TriangleMesh& coarse = coarse_level(h, level);
  return ShellProlongation(coarse.vertices, coarse.faces, h.to_finest[level],
                           h.levels.back().rest.vertices);
}

ShellProlongation next_level_prolongation(const MeshHierarchy& h, int level) {
  const TriangleMesh& coarse = coarse_level(h, level);
  return ShellProlongation(coarse.vertices, coarse.faces, h.to_next[level],
                           h.levels[level + 1].rest.vertices);
}

}  // namespace progsim
