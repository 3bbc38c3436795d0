#include "sim/handle_targets.hpp"

namespace progsim {

HandleTargets::HandleTargets(const Scene& scene, const ShellModel& model) {
  for (std::size_t h = 0; h < scene.handles.size(); ++h) {
    const Handle& handle = scene.handles[h];
    motions_.push_back(handle.motion);
    for (int v : handle.vertices) {
      const int global = model.vertex_offset[handle.body] + v;
      vertices_.push_back(global);
      handle_of_.push_back(static_cast<int>(h));
      rest_.push_back(model.rest.vertices.row(global).transpose());
    }
  }
}

std::vector<bool> HandleTargets::fixed_dofs(int num_vertices) const {
  std::vector<bool> fixed(3 * static_cast<std::size_t>(num_vertices), false);
  for (int v : vertices_)
    for (int k = 0; k < 3; ++k) fixed[3 * v + k] = true;
  return fixed;
}

void HandleTargets::apply(double t, Vector& x) const {
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    x.segment<3>(3 * vertices_[i]) = motions_[handle_of_[i]].position(rest_[i], t);
  }
}

}  // namespace progsim
