#pragma once
/// @file The inertia term of the incremental potential.
#include "energy/energy_term.hpp"

namespace progsim {

/// E(x) = 1/(2h²) (x − x̂)ᵀ M (x − x̂) with lumped mass M (DESIGN.md §2, implicit Euler
/// incremental potential; Li et al. 2020 eq. 2). Hessian M/h², already PSD.
class Inertia : public EnergyTerm {
 public:
  /// @param vertex_masses lumped masses (|V|), kg
  /// @param time_step h, s
  Inertia(Eigen::VectorXd vertex_masses, double time_step);

  const char* name() const override { return "inertia"; }
  double value(const Vector& x) const override;
  void add_gradient(const Vector& x, Vector& g) const override;
  std::size_t hessian_entry_count() const override { return masses_.size() * 3; }
  void hessian_pattern(int* rows, int* cols) const override;
  void hessian_values(const Vector& x, bool project_psd, double* values) const override;

  /// Sets the predicted position x̂ = xᵗ + h vᵗ (3|V|).
  void set_target(const Vector& x_hat) { target_ = x_hat; }
  const Vector& target() const { return target_; }
  /// Sets h (s).
  void set_time_step(double time_step) { time_step_ = time_step; }

 private:
  Eigen::VectorXd masses_;
  double time_step_;
  Vector target_;
};

}  // namespace progsim
