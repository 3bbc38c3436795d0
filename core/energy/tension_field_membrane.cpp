#include "energy/tension_field_membrane.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "common/error.hpp"

namespace progsim {
namespace {

enum class State { slack, wrinkled, taut };

/// Pipkin's (1986) test: slack if σ₁ ≤ 1, wrinkled if ∂Ψ/∂σ₂ < 0, with σ₂ ∂Ψ/∂σ₂ = μ(σ₂² − 1)
/// + λ ln(σ₁σ₂) for Ψ of NeoHookeanMembrane; taut otherwise.
State state_of(const StretchSpectrum& s, double mu, double lambda) {
  if (s.sigma1 <= 1.0) return State::slack;
  if (s.sigma2 <= 0.0) return State::wrinkled;
  return mu * (s.sigma2 * s.sigma2 - 1.0) + lambda * std::log(s.sigma1 * s.sigma2) < 0.0
             ? State::wrinkled
             : State::taut;
}

/// Uniaxial tension at stretch σ₁ > 1: g(σ₁) = Ψ(σ₁, σ₂*) and its first two derivatives.
struct Uniaxial {
  double energy;  ///< g = Ψ(σ₁, σ₂*) (Pa)
  double slope;   ///< g' = ∂Ψ/∂σ₁ (envelope theorem: ∂Ψ/∂σ₂ = 0 at σ₂*)
  double curve;   ///< g'' = Ψ₁₁ − Ψ₁₂²/Ψ₂₂ (σ₂* follows σ₁)
};

/// σ² − 1 − 2 ln σ = e^{2a} − 1 − 2a from a = ln σ, each axis's share of the neo-Hookean shear
/// term; near a = 0 by its series Σ_{k≥2} (2a)^k/k!, whose terms do not cancel.
double axis_shear(double a) {
  if (std::abs(a) >= 0.1) return std::expm1(2.0 * a) - 2.0 * a;
  double term = 2.0 * a * a, sum = 0.0;  // (2a)²/2!
  for (int k = 3; k < 20; ++k) {
    sum += term;
    term *= 2.0 * a / k;
  }
  return sum;
}

Uniaxial uniaxial(double s1, double mu, double lambda) {
  // σ₂* solves μ(σ₂² − 1) + λ ln(σ₁σ₂) = 0. In z = ln σ₂ the left side is convex and, where
  // Newton goes, increasing: everywhere for λ ≥ 0; for ν < 0 (λ < 0) the root lies at z > 0,
  // where the slope 2μe^{2z} + λ ≥ 2μ + λ = E/(1 − ν²) > 0. So Newton from z = 0 lands right of
  // the root after at most one step and then descends monotonically to it.
  const double a1 = std::log(s1);
  double z = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double h = mu * std::expm1(2.0 * z) + lambda * (a1 + z);
    const double step = h / (2.0 * mu * std::exp(2.0 * z) + lambda);
    z -= step;
    if (std::abs(step) <= 1e-15 * (1.0 + std::abs(z))) break;
  }
  const double s2 = std::exp(z), log_j = a1 + z;
  Uniaxial u;
  // Ψ = μ/2 (σ₁² + σ₂² − 2 − 2 ln σ₁σ₂) + λ/2 (ln σ₁σ₂)² (PSQ footnote 1, principal stretches).
  u.energy = 0.5 * mu * (axis_shear(a1) + axis_shear(z)) + 0.5 * lambda * log_j * log_j;
  u.slope = mu * (s1 - 1.0 / s1) + lambda * log_j / s1;
  const double p11 = mu * (1.0 + 1.0 / (s1 * s1)) + lambda * (1.0 - log_j) / (s1 * s1);
  const double p22 = mu * (1.0 + 1.0 / (s2 * s2)) + lambda * (1.0 - log_j) / (s2 * s2);
  const double p12 = lambda / (s1 * s2);
  u.curve = p11 - p12 * p12 / p22;
  return u;
}

}  // namespace

TensionFieldMembrane::TensionFieldMembrane(const Positions& rest, const Faces& faces,
                                           const std::vector<ShellMaterial>& face_materials,
                                           double compression_share)
    : NeoHookeanMembrane(rest, faces, face_materials), share_(compression_share) {
  if (!(compression_share >= 0.0 && compression_share < 1.0))
    fail(Status::invalid_argument, "tension-field membrane: compression share " +
                                       std::to_string(compression_share) + " is outside [0, 1)");
}

double TensionFieldMembrane::element_value(int e, const LocalVector& xe) const {
  const Element& el = elements_[e];
  const StretchSpectrum s(deformation_gradient(el.beta, xe));
  const State state = state_of(s, el.mu, el.lambda);
  if (state == State::taut) return NeoHookeanMembrane::element_value(e, xe);
  const double relaxed =
      state == State::slack ? 0.0 : el.weight * uniaxial(s.sigma1, el.mu, el.lambda).energy;
  if (share_ == 0.0) return relaxed;  // ε Ψ would be 0 · ∞ on a collapsed face
  // W_ε = (1 − ε) W + ε Ψ
  return (1.0 - share_) * relaxed + share_ * NeoHookeanMembrane::element_value(e, xe);
}

void TensionFieldMembrane::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  const Element& el = elements_[e];
  const Mat32 f = deformation_gradient(el.beta, xe);
  const StretchSpectrum s(f);
  const State state = state_of(s, el.mu, el.lambda);
  NeoHookeanMembrane::element_gradient(e, xe, g);
  if (state == State::taut) return;
  scale_full_part(g);
  if (state == State::slack) return;
  // ∂W/∂F = g'(σ₁) u₁v₁ᵀ with u₁ = F v₁/σ₁; ∂E/∂x_a = t Ā (∂W/∂F) β_a.
  const double slope = uniaxial(s.sigma1, el.mu, el.lambda).slope;
  const Mat32 p = ((1.0 - share_) * slope / s.sigma1) * (f * s.v1) * s.v1.transpose();
  for (int v = 0; v < 3; ++v) g.segment<3>(3 * v) += el.weight * (p * el.beta.row(v).transpose());
}

NeoHookeanMembrane::Matrix6 TensionFieldMembrane::wrinkled_stress_derivative(
    int e, const Mat32& f, const StretchSpectrum& s, bool project) const {
  const Element& el = elements_[e];
  const Uniaxial g = uniaxial(s.sigma1, el.mu, el.lambda);
  const Vec3 u1 = f * s.v1 / s.sigma1;
  Vec3 u2 = f * s.v2;
  u2 -= u1.dot(u2) * u1;
  // A face collapsed to a segment has no u₂; any unit vector normal to u₁ gives the same
  // Hessian then (twist and flip share the eigenvalue g'/σ₁ with the out-of-plane mode).
  u2 = u2.norm() > 1e-12 * s.sigma1 ? Vec3(u2.normalized()) : Vec3(u1.unitOrthogonal());
  const Vec3 n = u1.cross(u2);
  Matrix6 hf = Matrix6::Zero();
  const auto add_mode = [&hf, project](double eigenvalue, const Mat32& mode) {
    if (project && eigenvalue <= 0.0) return;
    const Eigen::Map<const Eigen::Matrix<double, 6, 1>> m(mode.data());
    hf.noalias() += eigenvalue * m * m.transpose();
  };
  // ∂²W/∂F² = g'' ∇σ₁∇σ₁ᵀ + g' ∇²σ₁; the eigensystem of ∇²σ₁ for a 3×2 F (Smith et al. 2019 with
  // Ψ = σ₁): twist 1/(σ₁+σ₂), flip 1/(σ₁−σ₂), out-of-plane n v₁ᵀ 1/σ₁, the rest 0.
  constexpr double kInvSqrt2 = 0.70710678118654752440;
  add_mode(g.curve, u1 * s.v1.transpose());
  add_mode(g.slope / (s.sigma1 + s.sigma2),
           kInvSqrt2 * (u1 * s.v2.transpose() - u2 * s.v1.transpose()));
  add_mode(g.slope / (s.sigma1 - s.sigma2),
           kInvSqrt2 * (u1 * s.v2.transpose() + u2 * s.v1.transpose()));
  add_mode(g.slope / s.sigma1, n * s.v1.transpose());
  return hf;
}

template <typename Derivative>
void TensionFieldMembrane::scale_full_part(Derivative& d) const {
  if (share_ == 0.0)
    d.setZero();  // no NaN of a collapsed face's Ψ
  else
    d *= share_;
}

void TensionFieldMembrane::blended_hessian(int e, const LocalVector& xe, bool project,
                                           LocalMatrix& h) const {
  const Element& el = elements_[e];
  const Mat32 f = deformation_gradient(el.beta, xe);
  const StretchSpectrum s(f);
  const State state = state_of(s, el.mu, el.lambda);
  if (project)
    NeoHookeanMembrane::element_projected_hessian(e, xe, h);
  else
    NeoHookeanMembrane::element_hessian(e, xe, h);
  if (state == State::taut) return;
  scale_full_part(h);
  if (state == State::slack) return;
  LocalMatrix relaxed;
  pull_back(e, (1.0 - share_) * wrinkled_stress_derivative(e, f, s, project), relaxed);
  h += relaxed;
}

void TensionFieldMembrane::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  blended_hessian(e, xe, false, h);
}

void TensionFieldMembrane::element_projected_hessian(int e, const LocalVector& xe,
                                                     LocalMatrix& h) const {
  blended_hessian(e, xe, true, h);
}

}  // namespace progsim
