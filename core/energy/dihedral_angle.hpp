#pragma once
/// @file The signed dihedral angle of a hinge (two triangles sharing an edge) and its exact
/// first and second derivatives (Bridson et al. 2003; Tamstorf & Grinspun 2013). Shared by the
/// hinge bending term and the mid-edge shape operator.
#include "common/types.hpp"

namespace progsim {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

/// Signed dihedral angle θ (radians, in (−π, π]) of the hinge with edge x0 → x1, first face
/// (x0, x1, x2) and second face (x1, x0, x3): θ = atan2((n₁ × n₂)·ê, n₁·n₂) with
/// n₁ = (x1 − x0) × (x2 − x0), n₂ = (x3 − x0) × (x1 − x0). θ = 0 for a flat hinge; θ < 0
/// when the opposite vertices move to the side n₁ points to. Finite for any input (atan2(0, 0)
/// = 0 for degenerate faces); accurate near 0 and near ±π.
double dihedral_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);

/// The quantities ∇θ and ∇²θ of dihedral_angle() are built from, for one hinge at the stacked
/// positions (x0, x1, x2, x3) (12). Derivatives are finite as long as both faces have non-zero
/// area.
struct HingeFrame {
  Vec3 e, w, u;   ///< x1 − x0, x2 − x0, x3 − x0
  Vec3 n1, n2;    ///< face normals scaled by twice the area: e × w, u × e
  double length;  ///< ‖e‖
  double n1_sq;   ///< ‖n₁‖²
  double n2_sq;   ///< ‖n₂‖²
  double t1, t2;  ///< projections of x2, x3 onto the edge: (w·e)/‖e‖², (u·e)/‖e‖²
  Vec3 m1, m2;  ///< ‖e‖ n_i/‖n_i‖² = n̂_i / h_i (h_i the height of face i over the edge)

  explicit HingeFrame(const Vector12& xe);

  /// θ, as dihedral_angle() (rad).
  double angle() const;
  /// ∇θ (12): opposite vertices −‖e‖ n_i/‖n_i‖², edge vertices the combination weighted by
  /// the opposite vertices' projections onto the edge (Bridson et al. 2003, "Simulation of
  /// clothing with folds and wrinkles", bending force directions u₁..u₄).
  Vector12 angle_gradient() const;
  /// ∇²θ (12×12), the exact derivative of angle_gradient() (cf. Tamstorf & Grinspun 2013),
  /// symmetric bit for bit.
  Matrix12 angle_hessian() const;
};

}  // namespace progsim
