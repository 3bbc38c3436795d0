#include "sim/handle_reactions.hpp"

#include <Eigen/Geometry>

namespace progsim {

std::vector<HandleReaction> handle_reactions(const HandleTargets& handles, const Vector& x,
                                             const Vector& gradient) {
  const std::vector<int>& dofs = handles.dofs();
  const std::vector<int>& owner = handles.dof_handles();
  std::vector<HandleReaction> out(handles.num_handles());
  std::vector<int> count(out.size(), 0), last_vertex(out.size(), -1);
  for (std::size_t i = 0; i < dofs.size(); ++i) {  // centroids of the held vertices
    const int v = dofs[i] / 3;
    if (v == last_vertex[owner[i]]) continue;
    last_vertex[owner[i]] = v;
    out[owner[i]].point += x.segment<3>(3 * v);
    ++count[owner[i]];
  }
  for (std::size_t h = 0; h < out.size(); ++h)
    if (count[h] > 0) out[h].point /= count[h];
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    HandleReaction& r = out[owner[i]];
    const int v = dofs[i] / 3, k = dofs[i] % 3;
    const Vec3 force = gradient[dofs[i]] * Vec3::Unit(k);  // R_d = ∂E/∂x_d
    r.force += force;
    r.moment += (x.segment<3>(3 * v) - r.point).cross(force);
  }
  return out;
}

}  // namespace progsim
