#pragma once
/// @file Where a scene's scripted obstacles are at a given time.
#include <vector>

#include "contact/collision_mesh.hpp"
#include "scene/scene.hpp"

namespace progsim {

/// The obstacles of a scene with their rigid scripts; all obstacle vertices stacked in scene
/// order (the order of the collision mesh's obstacle vertices).
class ObstacleScript {
 public:
  explicit ObstacleScript(const Scene& scene);

  /// Stacked obstacle vertex positions at time t (s): (|V_obstacles| × 3).
  Positions at(double t) const;
  /// Whether any obstacle moves at all.
  bool moves() const { return moves_; }
  /// The obstacles at t = 0 as surfaces to merge into a collision mesh (borrowed from this).
  std::vector<ObstacleSurface> surfaces() const;

 private:
  std::vector<Obstacle> obstacles_;
  bool moves_ = false;
};

}  // namespace progsim
