#pragma once
/// @file Gravitational potential energy.
#include "energy/energy_term.hpp"

namespace progsim {

/// E(x) = −Σ_i m_i g·x_i (linear; no Hessian entries).
class Gravity : public EnergyTerm {
 public:
  /// @param vertex_masses lumped masses (|V|), kg
  /// @param acceleration g, m/s²
  Gravity(Eigen::VectorXd vertex_masses, const Vec3& acceleration);

  const char* name() const override { return "gravity"; }
  double value(const Vector& x) const override;
  void add_gradient(const Vector& x, Vector& g) const override;
  std::size_t hessian_entry_count() const override { return 0; }
  void hessian_pattern(int*, int*) const override {}
  void hessian_values(const Vector&, bool, double*) const override {}

  void set_acceleration(const Vec3& acceleration) { acceleration_ = acceleration; }
  const Vec3& acceleration() const { return acceleration_; }

 private:
  Eigen::VectorXd masses_;
  Vec3 acceleration_;
};

}  // namespace progsim
