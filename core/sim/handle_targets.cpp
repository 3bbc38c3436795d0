#include "sim/handle_targets.hpp"

#include "common/error.hpp"

namespace progsim {

std::vector<int> vertex_handles(const Scene& scene, const ShellModel& model) {
  std::vector<int> handle_of(model.rest.num_vertices(), -1);
  for (std::size_t h = 0; h < scene.handles.size(); ++h) {
    const Handle& handle = scene.handles[h];
    for (int v : handle.vertices)
      handle_of[model.vertex_offset[handle.body] + v] = static_cast<int>(h);
  }
  return handle_of;
}

HandleTargets::HandleTargets(const Scene& scene, const Positions& rest,
                             const std::vector<int>& vertex_handle) {
  for (const Handle& handle : scene.handles) motions_.push_back(handle.motion);
  for (int v = 0; v < static_cast<int>(vertex_handle.size()); ++v) {
    const int h = vertex_handle[v];
    if (h < 0) continue;
    if (h >= static_cast<int>(motions_.size()))
      fail(Status::invalid_argument, "vertex " + std::to_string(v) + " belongs to handle " +
                                         std::to_string(h) + " but the scene has " +
                                         std::to_string(motions_.size()) + " handles");
    for (int k = 0; k < 3; ++k) {
      if ((scene.handles[h].axes & (1u << k)) == 0) continue;
      dofs_.push_back(3 * v + k);
      dof_handle_.push_back(h);
      rest_.push_back(rest.row(v).transpose());
    }
  }
}

std::vector<bool> HandleTargets::fixed_dofs(int num_vertices) const {
  std::vector<bool> fixed(3 * static_cast<std::size_t>(num_vertices), false);
  for (int d : dofs_) fixed[d] = true;
  return fixed;
}

Vector HandleTargets::dof_targets(double t) const {
  Vector out(dofs_.size());
  for (std::size_t i = 0; i < dofs_.size(); ++i)
    out[i] = motions_[dof_handle_[i]].position(rest_[i], t)[dofs_[i] % 3];
  return out;
}

void HandleTargets::apply(double t, Vector& x) const {
  for (std::size_t i = 0; i < dofs_.size(); ++i)
    x[dofs_[i]] = motions_[dof_handle_[i]].position(rest_[i], t)[dofs_[i] % 3];
}

}  // namespace progsim
