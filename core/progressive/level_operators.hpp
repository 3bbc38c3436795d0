#pragma once
/// @file The prolongation operators a progressive driver needs between a hierarchy's levels,
/// built when first asked for and shared by the levels' simulations.
#include <memory>
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"
#include "hierarchy/shell_prolongation.hpp"
#include "scene/scene.hpp"

namespace progsim {

/// P^l_{l+1} (PSQ eq. 7) and P^l (eq. 9) of one hierarchy, each built once on first use.
/// Not thread-safe (the drivers are single-threaded; the operators themselves are immutable).
class LevelOperators {
 public:
  explicit LevelOperators(std::shared_ptr<const MeshHierarchy> hierarchy);

  /// P^l_{l+1}: level `level` (< finest) to the next finer one (PSQ eq. 7).
  const std::shared_ptr<const ShellProlongation>& next(int level) const;
  /// The operators that take level `level` (< finest) to the finest mesh, applied in turn:
  /// P^l alone (PSQ eq. 9) or P_{l+1}^l, …, P_L^{L−1}, as `prolongation` says. Throws
  /// Error(out_of_range) for a level that is not a coarse level.
  std::vector<std::shared_ptr<const ShellProlongation>> to_finest(
      int level, ProxyProlongation prolongation) const;

 private:
  std::shared_ptr<const MeshHierarchy> hierarchy_;
  mutable std::vector<std::shared_ptr<const ShellProlongation>> next_;    // lazily built
  mutable std::vector<std::shared_ptr<const ShellProlongation>> direct_;  // lazily built
};

}  // namespace progsim
