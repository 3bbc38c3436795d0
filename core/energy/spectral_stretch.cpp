#include "energy/spectral_stretch.hpp"

namespace progsim {
namespace {

/// Below this ratio (σ₁ − σ₂)/scale the divided difference of g' is replaced by the mean of
/// g''(λ₁), g''(λ₂). Both errors are relative to the Hessian scale: the mean is off by
/// ~(Δσ/scale)², the divided difference by cancellation ~ε scale/Δσ; ε^(1/3) ≈ 6e-6 balances them.
constexpr double kIsotropicRatio = 1e-5;

}  // namespace

SpectralDerivatives::SpectralDerivatives(const StretchSpectrum& spectrum,
                                         const StretchDerivatives h[2], double scale)
    : g1{0.0, 0.0}, g2{0.0, 0.0}, divided(0.0) {
  const double sigma[2] = {spectrum.sigma1, spectrum.sigma2};
  for (int i = 0; i < 2; ++i) {
    if (h[i].slope == 0.0 && h[i].curvature == 0.0) continue;  // flat: g ≡ 0 near λ_i
    const double s = sigma[i];
    g1[i] = h[i].slope / (2.0 * s);
    g2[i] = (h[i].curvature - h[i].slope / s) / (4.0 * s * s);
  }
  const double gap = sigma[0] - sigma[1];  // ≥ 0
  if (gap > kIsotropicRatio * scale)
    divided = (g1[0] - g1[1]) / (gap * (sigma[0] + sigma[1]));
  else
    divided = 0.5 * (g2[0] + g2[1]);  // → g''(λ) as λ₁ − λ₂ → 0
}

FaceVector spectral_gradient(const Mat32& f, const StretchSpectrum& spectrum,
                             const SpectralDerivatives& d, const Mat32& beta, double w) {
  // dΦ = ⟨S, dFᵀF + FᵀdF⟩ = ⟨2FS, dF⟩, and ∂Φ/∂x_a = (∂Φ/∂F) β_a.
  const Mat2 s = d.g1[0] * spectrum.v1 * spectrum.v1.transpose() +
                 d.g1[1] * spectrum.v2 * spectrum.v2.transpose();
  const Mat32 p = (2.0 * w) * (f * s);
  FaceVector g;
  for (int a = 0; a < 3; ++a) g.segment<3>(3 * a) = p * beta.row(a).transpose();
  return g;
}

FaceMatrix spectral_hessian(const Mat32& f, const StretchSpectrum& spectrum,
                            const SpectralDerivatives& d, const Mat32& beta, double w) {
  const Vec2& v1 = spectrum.v1;
  const Vec2& v2 = spectrum.v2;
  // d²Φ[dC, dC] = Σ_i g''(λ_i)(v_iᵀ dC v_i)² + 2 δ (v₁ᵀ dC v₂)², δ the divided difference;
  // plus ⟨S, d²C⟩ with d²C = 2 dFᵀdF. With dF = Σ_a dx_a β_aᵀ:
  // v_iᵀ dC v_j = Σ_a dx_a · [(β_a·v_j) F v_i + (β_a·v_i) F v_j], and
  // ⟨S, dFᵀdF⟩ = Σ_ab (β_aᵀ S β_b) dx_a·dx_b.
  const Vec3 fv1 = f * v1, fv2 = f * v2;
  FaceVector q1, q2, q12;
  for (int a = 0; a < 3; ++a) {
    const Vec2 b = beta.row(a).transpose();
    const double b1 = b.dot(v1), b2 = b.dot(v2);
    q1.segment<3>(3 * a) = (2.0 * b1) * fv1;
    q2.segment<3>(3 * a) = (2.0 * b2) * fv2;
    q12.segment<3>(3 * a) = b2 * fv1 + b1 * fv2;
  }
  const Mat2 s = d.g1[0] * v1 * v1.transpose() + d.g1[1] * v2 * v2.transpose();
  const Mat3 bsb = beta * s * beta.transpose();  // β_aᵀ S β_b
  FaceMatrix h;
  h.noalias() = (w * d.g2[0]) * q1 * q1.transpose();
  h.noalias() += (w * d.g2[1]) * q2 * q2.transpose();
  h.noalias() += (2.0 * w * d.divided) * q12 * q12.transpose();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      h.block<3, 3>(3 * a, 3 * b).diagonal().array() += 2.0 * w * bsb(a, b);
  return h;
}

}  // namespace progsim
