#pragma once
/// @file The consistency penalty of progressive dynamics (VPD eq. 4, proposed by PD++).
#include "energy/inertia.hpp"

namespace progsim {

/// E(x) = w/(2h²) (x − y)ᵀ M (x − y), y = P(x_{l−1}^{t+1}) the coarser level's frame at the end
/// of the step prolonged to this level (VPD eq. 4: a mass-weighted quadratic with a user
/// weight w; scaled like the inertia so that w is dimensionless). The inertia term's algebra
/// with masses w·m; set_target() sets y.
class ConsistencyPenalty final : public Inertia {
 public:
  /// @param vertex_masses the level's lumped masses (|V|), kg
  /// @param weight w > 0
  /// @param time_step h, s
  ConsistencyPenalty(const Eigen::VectorXd& vertex_masses, double weight, double time_step)
      : Inertia(weight * vertex_masses, time_step) {}

  const char* name() const override { return "consistency_penalty"; }
};

}  // namespace progsim
