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

/// The handle vertices of one level (indices into its model) and their rest positions;
/// evaluates each handle's rigid script.
class HandleTargets {
 public:
  /// `vertex_handle` (|V|): per vertex of `rest`, its handle in scene.handles or −1. On a
  /// coarse level these are the hierarchy's level_groups(), whose rest positions are input rest
  /// positions of the same handle, so the rigid script is exact on every level.
  HandleTargets(const Scene& scene, const Positions& rest, const std::vector<int>& vertex_handle);
  HandleTargets() = default;  ///< no handles

  /// Fixed-DOF mask (3|V|) with the three DOFs of every handle vertex set.
  std::vector<bool> fixed_dofs(int num_vertices) const;

  /// Writes each handle vertex's target at time t (s) into x (3|V|):
  /// x_i(t) = c + R(ω t)(x̄_i − c) + v t + offset.
  void apply(double t, Vector& x) const;

  /// Targets of every handle vertex at time t, in the order of vertices() (one row each).
  Positions targets(double t) const;

  /// The handle vertices (indices into the level's model).
  const std::vector<int>& vertices() const { return vertices_; }
  bool empty() const { return vertices_.empty(); }

 private:
  std::vector<int> vertices_;   // vertex index per handle vertex
  std::vector<int> handle_of_;  // which handle each entry belongs to
  std::vector<Vec3> rest_;      // rest position per entry
  std::vector<HandleMotion> motions_;
};

}  // namespace progsim
