#pragma once
/// @file Where scripted handle vertices are at a given time.
#include <vector>

#include "common/types.hpp"
#include "scene/scene.hpp"
#include "sim/shell_model.hpp"

namespace progsim {

/// The handle vertices of a scene (global indices into the merged model) and their rest
/// positions; evaluates each handle's rigid script.
class HandleTargets {
 public:
  HandleTargets(const Scene& scene, const ShellModel& model);

  /// Fixed-DOF mask (3|V|) with the three DOFs of every handle vertex set.
  std::vector<bool> fixed_dofs(int num_vertices) const;

  /// Writes each handle vertex's target at time t (s) into x (3|V|):
  /// x_i(t) = c + R(ω t)(x̄_i − c) + v t + offset.
  void apply(double t, Vector& x) const;

  bool empty() const { return vertices_.empty(); }

 private:
  std::vector<int> vertices_;   // global vertex index per handle vertex
  std::vector<int> handle_of_;  // which handle each entry belongs to
  std::vector<Vec3> rest_;      // rest position per entry
  std::vector<HandleMotion> motions_;
};

}  // namespace progsim
