#include "sim/simulation_level.hpp"

#include <algorithm>
#include <numeric>

#include "common/error.hpp"
#include "energy/lumped_mass.hpp"

namespace progsim {
namespace {

/// The body owning input (finest) vertex v.
int body_of(const ShellModel& finest, int v) {
  const auto it = std::upper_bound(finest.vertex_offset.begin(), finest.vertex_offset.end(), v);
  return static_cast<int>(it - finest.vertex_offset.begin()) - 1;
}

}  // namespace

ShellModel level_shell_model(const ShellModel& finest, const MeshHierarchy& hierarchy, int level) {
  if (level < 0 || level > hierarchy.finest())
    fail(Status::out_of_range, "level " + std::to_string(level) + " is not in [0, " +
                                   std::to_string(hierarchy.finest()) + "]");
  const HierarchyLevel& l = hierarchy.levels[level];
  const std::vector<int>& input = l.input_vertex;
  const int bodies = static_cast<int>(finest.vertex_offset.size()) - 1;
  ShellModel model;
  model.rest.vertices = l.rest.vertices;
  for (int b = 0; b <= bodies; ++b)
    model.vertex_offset.push_back(static_cast<int>(
        std::lower_bound(input.begin(), input.end(), finest.vertex_offset[b]) - input.begin()));
  std::vector<int> face_body(l.rest.num_faces());
  for (int f = 0; f < l.rest.num_faces(); ++f)
    face_body[f] = body_of(finest, input[l.rest.faces(f, 0)]);
  std::vector<int> order(face_body.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return face_body[a] < face_body[b]; });
  model.rest.faces.resize(l.rest.num_faces(), 3);
  model.face_offset.assign(bodies + 1, 0);
  for (int k = 0; k < static_cast<int>(order.size()); ++k) {
    model.rest.faces.row(k) = l.rest.faces.row(order[k]);
    model.face_materials.push_back(finest.face_materials[finest.face_offset[face_body[order[k]]]]);
    ++model.face_offset[face_body[order[k]] + 1];
  }
  std::partial_sum(model.face_offset.begin(), model.face_offset.end(), model.face_offset.begin());
  model.vertex_masses =
      lumped_vertex_masses(model.rest.vertices, model.rest.faces, model.face_materials);
  model.topology = build_topology(model.rest.faces, model.rest.num_vertices());
  return model;
}

void check_hierarchy_matches(const MeshHierarchy& hierarchy, const TriangleMesh& finest,
                             const std::vector<int>& vertex_handle, std::size_t num_handles) {
  const TriangleMesh& mesh = hierarchy.levels.back().rest;
  if (!same_array(mesh.vertices, finest.vertices) || !same_array(mesh.faces, finest.faces))
    fail(Status::invalid_argument,
         "the hierarchy's finest level (" + std::to_string(mesh.num_vertices()) + " vertices, " +
             std::to_string(mesh.num_faces()) + " faces) is not the scene's mesh (" +
             std::to_string(finest.num_vertices()) + " vertices, " +
             std::to_string(finest.num_faces()) + " faces)");
  if (hierarchy.num_levels() == 1) return;  // a single level has no decimated handles
  const auto handles = static_cast<int>(num_handles);
  for (std::size_t v = 0; v < vertex_handle.size(); ++v) {
    const int group = hierarchy.input_group[v];
    const bool group_not_a_handle_yet = vertex_handle[v] < 0 && group >= handles;
    if (vertex_handle[v] != group && !group_not_a_handle_yet)
      fail(Status::invalid_argument,
           "vertex " + std::to_string(v) + " is in handle " + std::to_string(vertex_handle[v]) +
               " of the scene but in group " + std::to_string(group) +
               " of the hierarchy: build the hierarchy with the scene's handles as vertex groups "
               "(C ABI: ps_hierarchy_def.pinned_vertices or vertex_group_ids; handle i is group "
               "i)");
  }
}

Eigen::VectorXd prolonged_masses(
    const std::vector<std::shared_ptr<const ShellProlongation>>& to_finest,
    const Eigen::VectorXd& finest_masses) {
  Eigen::VectorXd masses = finest_masses;
  for (auto op = to_finest.rbegin(); op != to_finest.rend(); ++op)
    masses = (*op)->intrinsic().transpose() * masses;  // m_k = U_kᵀ m_{k+1}
  return masses;
}

}  // namespace progsim
