#include "hierarchy/mesh_hierarchy.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "hierarchy/decimation.hpp"
#include "hierarchy/expansion_coloring.hpp"
#include "mesh/mesh_validation.hpp"

namespace progsim {

std::vector<FaceCorners> level_input_faces(const HierarchyLevel& level) {
  std::vector<FaceCorners> faces(level.rest.num_faces());
  for (int f = 0; f < level.rest.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) faces[f][k] = level.input_vertex[level.rest.faces(f, k)];
  return faces;
}

std::vector<int> level_vertex_index(const MeshHierarchy& hierarchy, int level) {
  std::vector<int> index(hierarchy.levels.back().rest.num_vertices(), -1);
  const std::vector<int>& ids = hierarchy.levels[level].input_vertex;
  for (int i = 0; i < static_cast<int>(ids.size()); ++i) index[ids[i]] = i;
  return index;
}

std::vector<int> level_groups(const MeshHierarchy& hierarchy, int level) {
  std::vector<int> group = hierarchy.input_group;
  for (int c = 0; c < hierarchy.first_collapse[level]; ++c) {
    const CollapseRecord& record = hierarchy.collapses[c];
    group[record.kept] = std::max(group[record.kept], group[record.removed]);
  }
  std::vector<int> out;
  for (int v : hierarchy.levels[level].input_vertex) out.push_back(group[v]);
  return out;
}

std::vector<int> geometric_level_counts(int finest_vertices, double ratio, int count) {
  if (!(ratio > 1.0) || !std::isfinite(ratio) || count < 1 || count > 30)
    fail(Status::invalid_argument, "hierarchy: level ratio " + std::to_string(ratio) +
                                       " must be > 1 and the level count " + std::to_string(count) +
                                       " in 1 to 30");
  std::vector<int> counts;
  for (int k = count; k >= 1; --k)
    counts.push_back(static_cast<int>(std::lround(finest_vertices / std::pow(ratio, k))));
  if (counts.front() < 4)
    fail(Status::invalid_argument, "hierarchy: " + std::to_string(count) + " levels at ratio " +
                                       std::to_string(ratio) + " leave " +
                                       std::to_string(counts.front()) +
                                       " vertices on the coarsest (at least 4 needed)");
  return counts;
}

MeshHierarchy build_hierarchy(const TriangleMesh& mesh, const HierarchyOptions& options,
                              HierarchyProgress progress, void* user) {
  validate_mesh(mesh, "hierarchy mesh");
  MeshHierarchy hierarchy = decimate(mesh, options, progress, user);
  for (int l = 0; l < hierarchy.finest(); ++l)
    hierarchy.expansion_batches.push_back(
        expansion_batches(level_input_faces(hierarchy.levels[l]), hierarchy.collapses,
                          hierarchy.first_collapse[l + 1], hierarchy.first_collapse[l]));
  if (progress && !progress(user, 1.0, "expansion coloring"))
    fail(Status::cancelled, "hierarchy: cancelled by the progress callback");
  // The shape only: the batches were just computed from these records, so recomputing and
  // replaying them (check_hierarchy, for files) would redo this work. Tests replay them.
  check_hierarchy_structure(hierarchy);
  return hierarchy;
}

}  // namespace progsim
