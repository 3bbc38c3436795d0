#pragma once
/// @file Where scripted handle vertices are at a given time.
#include <vector>

#include "common/types.hpp"
#include "scene/scene.hpp"
#include "sim/shell_model.hpp"

namespace progsim {

/// Per vertex of the merged model, the index of the scene handle that holds it (−1: free).
/// A vertex listed by several handles follows the last one.
std::vector<int> vertex_handles(const Scene& scene, const ShellModel& model);

/// The handle vertices of one level (indices into its model), their rest positions and the
/// coordinates each handle prescribes (Handle::axes); evaluates each handle's rigid script.
class HandleTargets {
 public:
  /// `vertex_handle` (|V|): per vertex of `rest`, its handle in scene.handles or −1. On a
  /// coarse level these are the hierarchy's level_groups(), whose rest positions are input rest
  /// positions of the same handle, so the rigid script is exact on every level.
  HandleTargets(const Scene& scene, const Positions& rest, const std::vector<int>& vertex_handle);
  HandleTargets() = default;  ///< no handles

  /// Fixed-DOF mask (3|V|): the prescribed coordinates of every handle vertex.
  std::vector<bool> fixed_dofs(int num_vertices) const;

  /// The prescribed DOFs (indices 3v + k), in the order dof_targets() fills.
  const std::vector<int>& dofs() const { return dofs_; }

  /// Writes each prescribed coordinate's target at time t (s) into x (3|V|), the others
  /// untouched: x_i(t) = c + R(ω t)(x̄_i − c) + v t + offset.
  void apply(double t, Vector& x) const;

  /// Targets of the prescribed DOFs at time t, in the order of dofs().
  Vector dof_targets(double t) const;

  /// Number of scene handles (some may hold no vertex of this level's model).
  int num_handles() const { return static_cast<int>(motions_.size()); }

  /// The handle each prescribed DOF belongs to, in the order of dofs().
  const std::vector<int>& dof_handles() const { return dof_handle_; }

  bool empty() const { return dofs_.empty(); }

 private:
  std::vector<int> dofs_;        // prescribed DOF 3v + k
  std::vector<int> dof_handle_;  // which handle each prescribed DOF belongs to
  std::vector<Vec3> rest_;       // rest position of each prescribed DOF's vertex
  std::vector<HandleMotion> motions_;
};

}  // namespace progsim
