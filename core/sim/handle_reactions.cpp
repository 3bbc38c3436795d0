#include "sim/handle_reactions.hpp"

#include <Eigen/Geometry>

namespace progsim {
namespace {

/// Calls visit(dof, handle) for every prescribed and every carried DOF of `handles`.
template <class Visit>
void for_each_held_dof(const HandleTargets& handles, Visit visit) {
  for (std::size_t i = 0; i < handles.dofs().size(); ++i)
    visit(handles.dofs()[i], handles.dof_handles()[i]);
  for (std::size_t i = 0; i < handles.carried_dofs().size(); ++i)
    visit(handles.carried_dofs()[i], handles.carried_dof_handles()[i]);
}

}  // namespace

std::vector<HandleReaction> handle_reactions(const HandleTargets& handles, const Vector& x,
                                             const Vector& gradient) {
  std::vector<HandleReaction> out(handles.num_handles());
  std::vector<int> count(out.size(), 0);
  std::vector<char> counted(x.size() / 3, 0);
  for_each_held_dof(handles, [&](int dof, int h) {  // centroids of the held vertices
    const int v = dof / 3;
    if (counted[v]) return;
    counted[v] = 1;
    out[h].point += x.segment<3>(3 * v);
    ++count[h];
  });
  for (std::size_t h = 0; h < out.size(); ++h)
    if (count[h] > 0) out[h].point /= count[h];
  for_each_held_dof(handles, [&](int dof, int h) {
    HandleReaction& r = out[h];
    const Vec3 force = gradient[dof] * Vec3::Unit(dof % 3);  // R_d = ∂E/∂x_d
    r.force += force;
    r.moment += (x.segment<3>(3 * (dof / 3)) - r.point).cross(force);
  });
  return out;
}

}  // namespace progsim
