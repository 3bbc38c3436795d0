#include "sim/handle_targets.hpp"

#include <map>

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
    if (h < 0 || h >= static_cast<int>(motions_.size())) continue;
    const Handle& handle = scene.handles[h];
    for (int k = 0; k < 3; ++k) {
      if ((handle.axes & (1u << k)) != 0)
        prescribed_.add(3 * v + k, h, rest.row(v).transpose());
      else if (handle.support == HandleSupport::rotation)
        carried_.add(3 * v + k, h, rest.row(v).transpose());
    }
  }
}

std::vector<bool> HandleTargets::fixed_dofs(int num_vertices) const {
  std::vector<bool> fixed(3 * static_cast<std::size_t>(num_vertices), false);
  for (int d : prescribed_.dofs) fixed[d] = true;
  return fixed;
}

std::vector<std::vector<int>> HandleTargets::shared_dofs() const {
  std::map<std::pair<int, int>, std::vector<int>> groups;  // (handle, axis) → its DOFs
  for (std::size_t i = 0; i < carried_.dofs.size(); ++i)
    groups[{carried_.handle[i], carried_.dofs[i] % 3}].push_back(carried_.dofs[i]);
  std::vector<std::vector<int>> out;
  for (auto& [key, dofs] : groups) out.push_back(std::move(dofs));
  return out;
}

std::vector<bool> HandleTargets::scripted_dofs(int num_vertices) const {
  std::vector<bool> scripted = fixed_dofs(num_vertices);
  for (int d : carried_.dofs) scripted[d] = true;
  return scripted;
}

double HandleTargets::target(const DofList& list, std::size_t i, double t) const {
  return motions_[list.handle[i]].position(list.rest[i], t)[list.dofs[i] % 3];
}

Vector HandleTargets::dof_targets(double t) const {
  Vector out(prescribed_.dofs.size());
  for (std::size_t i = 0; i < prescribed_.dofs.size(); ++i) out[i] = target(prescribed_, i, t);
  return out;
}

void HandleTargets::apply(double t, Vector& x) const {
  for (std::size_t i = 0; i < prescribed_.dofs.size(); ++i)
    x[prescribed_.dofs[i]] = target(prescribed_, i, t);
}

Vector HandleTargets::carried_targets(double t) const {
  Vector out(carried_.dofs.size());
  for (std::size_t i = 0; i < carried_.dofs.size(); ++i) out[i] = target(carried_, i, t);
  return out;
}

Vector HandleTargets::carried_rest() const {
  Vector out(carried_.dofs.size());
  for (std::size_t i = 0; i < carried_.dofs.size(); ++i)
    out[i] = carried_.rest[i][carried_.dofs[i] % 3];
  return out;
}

}  // namespace progsim
