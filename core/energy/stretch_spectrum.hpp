#pragma once
/// @file Principal stretches of a triangle's membrane deformation gradient, in closed form.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "energy/triangle_frame.hpp"

namespace progsim {

/// Singular values σ₁ ≥ σ₂ ≥ 0 of a 3×2 F and its right singular vectors v₁, v₂ (the
/// eigenvectors of C = FᵀF = V diag(σ₁², σ₂²) Vᵀ).
struct StretchSpectrum {
  double sigma1, sigma2;
  Vec2 v1, v2;

  explicit StretchSpectrum(const Mat32& f) {
    const double c00 = f.col(0).squaredNorm(), c11 = f.col(1).squaredNorm();
    const double c01 = f.col(0).dot(f.col(1));
    const double mean = 0.5 * (c00 + c11);
    const double half_gap = std::hypot(0.5 * (c00 - c11), c01);
    const double lambda1 = mean + half_gap;
    double lambda2 = mean - half_gap;
    // Strongly anisotropic (or collapsed) F: mean − half_gap has cancelled; det C/λ₁ has not.
    if (lambda2 < 0.5 * mean)
      lambda2 = lambda1 > 0.0 ? f.col(0).cross(f.col(1)).squaredNorm() / lambda1 : 0.0;
    sigma1 = std::sqrt(lambda1);
    sigma2 = std::sqrt(std::min(lambda2, lambda1));
    // Eigenvector of the larger eigenvalue of [[c00, c01], [c01, c11]] at angle θ with
    // (cos 2θ, sin 2θ) ∥ ((c00 − c11)/2, c01); any θ at C = cI (atan2(0, 0) = 0).
    const double angle = 0.5 * std::atan2(2.0 * c01, c00 - c11);
    v1 = Vec2(std::cos(angle), std::sin(angle));
    v2 = Vec2(-v1.y(), v1.x());
  }
};

}  // namespace progsim
