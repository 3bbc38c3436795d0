#pragma once
/// @file Lagged, smoothed Coulomb friction (IPC, Li et al. 2020, §5): a dissipative potential
/// over the contacts active at the start of a step, with normal forces and tangent frames
/// frozen there.
#include <vector>

#include "contact/contact_potential.hpp"
#include "energy/changing_pattern_term.hpp"

namespace progsim {

/// D(x) = Σ_k μ_k λ_k f0(‖u_k‖), u_k = P_kᵀ Σ_j w_kj (x_j − x_j⁰) the tangential slip of
/// contact k since the lagged state x⁰ (IPC eqs. 13–16), with f0 the C¹ smoothing of |·|
/// below the slip ε_x = ε_v h. Obstacle vertices contribute their scripted displacement, so a
/// moving obstacle drags what touches it. The Hessian is PSD by construction (IPC §5.2), so
/// the projected and exact Hessians agree. Only contacts with μ > 0 are kept.
class FrictionPotential : public ChangingPatternTerm {
 public:
  /// @param contact the barrier whose active pairs define the contacts (must outlive this)
  /// @param slip_threshold ε_x (m), > 0
  FrictionPotential(const ContactPotential& contact, double slip_threshold);

  /// Freezes the contacts, normal forces and frames at x0 (3|V|) and the current obstacle
  /// positions: call at the start of each step.
  void lag(const Vector& x0);
  /// Number of frictional contacts frozen by the last lag().
  int num_contacts() const { return static_cast<int>(contacts_.size()); }

  const char* name() const override { return "friction"; }
  double value(const Vector& x) const override;
  void add_gradient(const Vector& x, Vector& g) const override;
  void append_hessian_triplets(const Vector& x, bool project_psd,
                               std::vector<Eigen::Triplet<double>>& out) const override;

 private:
  struct Contact {
    ContactPoint point;
    Eigen::Matrix<double, 3, 2> basis;  ///< P: orthonormal tangent frame
  };
  /// The slip u_k (2) of contact k at x.
  Vec2 slip(const Contact& c, const Vector& x) const;
  /// Displacement of collision vertex v since the lagged state.
  Vec3 displacement(int v, const Vector& x) const;

  const ContactPotential& contact_;
  double epsilon_;
  std::vector<Contact> contacts_;
  Vector x0_;
  Positions obstacles0_;
};

/// f0(y) = −y³/(3ε²) + y²/ε + ε/3 for y < ε, else y (IPC eq. 15).
double friction_smoothing(double y, double epsilon);
/// f1(y)/y = f0'(y)/y: 2/ε − y/ε² for y < ε, else 1/y (IPC eq. 16).
double friction_smoothing_slope_over_y(double y, double epsilon);

}  // namespace progsim
