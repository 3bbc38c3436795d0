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
/// A rotation support's other coordinates are carried: they move by the script's change and
/// share one free translation per handle and axis (shared_dofs()).
class HandleTargets {
 public:
  /// `vertex_handle` (|V|): per vertex of `rest`, its handle in scene.handles or −1. On a
  /// coarse level these are the hierarchy's level_groups(), whose rest positions are input rest
  /// positions of the same handle, so the rigid script is exact on every level; a group from
  /// scene.handles.size() on is not a handle (yet) and holds nothing.
  HandleTargets(const Scene& scene, const Positions& rest, const std::vector<int>& vertex_handle);
  HandleTargets() = default;  ///< no handles

  /// Fixed-DOF mask (3|V|): the prescribed coordinates of every handle vertex.
  std::vector<bool> fixed_dofs(int num_vertices) const;

  /// The carried DOFs grouped per rotation support and axis, each group one unknown
  /// (Problem::set_shared_dofs).
  std::vector<std::vector<int>> shared_dofs() const;

  /// Mask (3|V|) of the DOFs a script moves: prescribed and carried.
  std::vector<bool> scripted_dofs(int num_vertices) const;

  /// The script's coordinate of every carried DOF at time t (the order of carried_dofs()): a
  /// rotation support's group turned as its script turns it, before its free translation.
  Vector carried_targets(double t) const;
  /// The carried DOFs' rest coordinates: the pose a group embodies before any step.
  Vector carried_rest() const;

  /// The carried DOFs (3v + k) and the handle of each.
  const std::vector<int>& carried_dofs() const { return carried_.dofs; }
  const std::vector<int>& carried_dof_handles() const { return carried_.handle; }

  /// The prescribed DOFs (indices 3v + k), in the order dof_targets() fills.
  const std::vector<int>& dofs() const { return prescribed_.dofs; }

  /// Writes each prescribed coordinate's target at time t (s) into x (3|V|), the others
  /// untouched: x_i(t) = c + R(ω t)(x̄_i − c) + v t + offset.
  void apply(double t, Vector& x) const;

  /// Targets of the prescribed DOFs at time t, in the order of dofs().
  Vector dof_targets(double t) const;

  /// Number of scene handles (some may hold no vertex of this level's model).
  int num_handles() const { return static_cast<int>(motions_.size()); }

  /// The handle each prescribed DOF belongs to, in the order of dofs().
  const std::vector<int>& dof_handles() const { return prescribed_.handle; }

  bool empty() const { return prescribed_.dofs.empty() && carried_.dofs.empty(); }

 private:
  /// DOFs 3v + k with their handle and their vertex's rest position.
  struct DofList {
    std::vector<int> dofs, handle;
    std::vector<Vec3> rest;
    void add(int dof, int h, const Vec3& x) {
      dofs.push_back(dof);
      handle.push_back(h);
      rest.push_back(x);
    }
  };
  /// The script's coordinate of DOF i of `list` at time t.
  double target(const DofList& list, std::size_t i, double t) const;

  DofList prescribed_;  // the handles' axes
  DofList carried_;     // rotation supports' coordinates outside their axes
  std::vector<HandleMotion> motions_;
};

}  // namespace progsim
