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
    vertices_.push_back(v);
    handle_of_.push_back(h);
    rest_.push_back(rest.row(v).transpose());
  }
}

std::vector<bool> HandleTargets::fixed_dofs(int num_vertices) const {
  std::vector<bool> fixed(3 * static_cast<std::size_t>(num_vertices), false);
  for (int v : vertices_)
    for (int k = 0; k < 3; ++k) fixed[3 * v + k] = true;
  return fixed;
}

Positions HandleTargets::targets(double t) const {
  Positions out(vertices_.size(), 3);
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    out.row(i) = motions_[handle_of_[i]].position(rest_[i], t).transpose();
  return out;
}

void HandleTargets::apply(double t, Vector& x) const {
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    x.segment<3>(3 * vertices_[i]) = motions_[handle_of_[i]].position(rest_[i], t);
  }
}

}  // namespace progsim
