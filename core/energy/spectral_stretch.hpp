#pragma once
/// @file Derivatives of a face energy Σ_i h(σ_i) of its membrane's principal stretches: a
/// spectral function of C = FᵀF, smooth also at σ₁ = σ₂ (Lewis 1996, "Derivatives of spectral
/// functions"; Lewis & Sendov 2001, "Twice differentiable spectral functions"). Shared by the
/// strain-limit barrier and the stretch-excess penalty.
#include "energy/stretch_spectrum.hpp"
#include "energy/triangle_frame.hpp"

namespace progsim {

using FaceVector = Eigen::Matrix<double, 9, 1>;
using FaceMatrix = Eigen::Matrix<double, 9, 9>;

/// h'(σ) and h''(σ) of one principal stretch's energy h (zero where h is flat).
struct StretchDerivatives {
  double slope = 0.0;
  double curvature = 0.0;
};

/// Φ(C) = Σ_i g(λ_i) with g(λ) = h(√λ), λ_i = σ_i², at one face.
struct SpectralDerivatives {
  double g1[2];  ///< g'(λ_i) = h'(σ_i)/(2σ_i)
  double g2[2];  ///< g''(λ_i) = (h''(σ_i) − h'(σ_i)/σ_i)/(4σ_i²)
  double divided;  ///< [g'(λ₁) − g'(λ₂)]/(λ₁ − λ₂), or its limit (g''(λ₁) + g''(λ₂))/2

  /// @param h h at σ₁ (h[0]) and σ₂ (h[1]); a zero entry for a singular value where h is flat
  /// @param scale distance in σ over which h changes: below σ₁ − σ₂ = 1e-5 × scale the divided
  ///        difference is replaced by the mean of g'' (no cancellation at σ₁ = σ₂)
  SpectralDerivatives(const StretchSpectrum& spectrum, const StretchDerivatives h[2], double scale);
};

/// w ∂Φ/∂x (9) of a face with F = Σ_a x_a β_aᵀ (β_a the rows of `beta`):
/// ∂Φ/∂F = 2F S with S = Σ_i g'(λ_i) v_i v_iᵀ (Lewis 1996).
FaceVector spectral_gradient(const Mat32& f, const StretchSpectrum& spectrum,
                             const SpectralDerivatives& d, const Mat32& beta, double w);

/// w ∂²Φ/∂x² (9×9) (Daleckii–Krein form, Lewis & Sendov 2001). PSD when h is convex and
/// non-decreasing on σ ≥ 0 (then Φ is a convex function of F, Lewis 1995).
FaceMatrix spectral_hessian(const Mat32& f, const StretchSpectrum& spectrum,
                            const SpectralDerivatives& d, const Mat32& beta, double w);

}  // namespace progsim
