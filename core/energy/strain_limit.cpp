#include "energy/strain_limit.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "energy/stretch_spectrum.hpp"

namespace progsim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Below this ratio (σ₁ − σ₂)/min(d₁, d₂) the divided difference of g' is replaced by the mean of
/// g''(λ₁), g''(λ₂). Both errors are relative to the Hessian scale: the mean is off by
/// ~(Δσ/d)², the divided difference by cancellation ~ε d/Δσ; ε^(1/3) ≈ 6e-6 balances them.
constexpr double kIsotropicRatio = 1e-5;

/// Growth of a held face's barrier stiffness per fit_limits call, and its cap.
constexpr double kHeldScaleGrowth = 4.0;
constexpr double kMaxHeldScale = 1e12;

/// Vertex indices of the faces, validated, as stencils.
std::vector<StencilTerm<3>::Stencil> face_stencils(const Positions& rest, const Faces& faces) {
  std::vector<StencilTerm<3>::Stencil> stencils(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = faces(f, k);
      if (v < 0 || v >= rest.rows())
        fail(Status::invalid_mesh, "strain_limit: face " + std::to_string(f) +
                                       " has vertex index " + std::to_string(v) + " out of range");
      stencils[f][k] = v;
    }
  return stencils;
}

/// h(σ) = b(s − σ, ŝ) and its first two σ-derivatives, for a distance d = s − σ ∈ (0, ŝ).
struct Barrier {
  double value;      ///< h = b(d) = −(d − ŝ)² ln(d/ŝ)
  double slope;      ///< h' = −b'(d) = 2(d − ŝ) ln(d/ŝ) + (d − ŝ)²/d ≥ 0
  double curvature;  ///< h'' = b''(d) = −2 ln(d/ŝ) − 4(d − ŝ)/d + (d − ŝ)²/d² ≥ 0

  Barrier(double d, double band) {
    const double r = d - band;                      // < 0
    const double log_ratio = std::log1p(r / band);  // ln(d/ŝ), accurate near d = ŝ
    const double q = r / d;
    value = -r * r * log_ratio;
    slope = 2.0 * r * log_ratio + r * q;
    curvature = -2.0 * log_ratio - 4.0 * q + q * q;
  }
};

/// Derivatives of Φ(C) = Σ_i g(λ_i(C)), g(λ) = h(√λ), at one face's C.
struct SpectralDerivatives {
  double g1[2];    ///< g'(λ_i) = h'(σ_i)/(2σ_i)
  double g2[2];    ///< g''(λ_i) = (h''(σ_i) − h'(σ_i)/σ_i)/(4σ_i²)
  double divided;  ///< [g'(λ₁) − g'(λ₂)]/(λ₁ − λ₂), or its limit
};

}  // namespace

StrainLimit::StrainLimit(const Positions& rest, const Faces& faces, std::vector<double> face_limits,
                         double band, double stiffness)
    : StencilTerm<3>(face_stencils(rest, faces), static_cast<int>(rest.rows())),
      band_(band),
      stiffness_(stiffness),
      num_vertices_(static_cast<int>(rest.rows())) {
  if (face_limits.size() != static_cast<std::size_t>(faces.rows()))
    fail(Status::invalid_argument, "strain_limit: " + std::to_string(face_limits.size()) +
                                       " face limits for " + std::to_string(faces.rows()) +
                                       " faces");
  set_stiffness(stiffness);
  if (!(band > 0.0) || !std::isfinite(band))
    fail(Status::invalid_argument,
         "strain_limit: band must be > 0 (got " + std::to_string(band) + ")");
  elements_.resize(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const double limit = face_limits[f];
    if (!(limit > 1.0) || !std::isfinite(limit))
      fail(Status::invalid_argument, "strain_limit: limit of face " + std::to_string(f) +
                                         " must be > 1 (got " + std::to_string(limit) + ")");
    if (!(band < limit - 1.0))
      fail(Status::invalid_argument, "strain_limit: band " + std::to_string(band) +
                                         " must be < limit − 1 = " + std::to_string(limit - 1.0) +
                                         " (face " + std::to_string(f) + ")");
    const TriangleFrame frame = rest_triangle_frame(rest, faces, f, "strain_limit");
    Element& el = elements_[f];
    el.beta = frame.beta;
    el.area = frame.area;
    el.limit = el.own_limit = limit;
  }
}

int StrainLimit::fit_limits(const Vector& x, FitAfter after) {
  int raised = 0;
#pragma omp parallel for reduction(+ : raised) schedule(static) if (num_elements() >= kMinParallelItems)
  for (int e = 0; e < num_elements(); ++e) {
    Element& el = elements_[e];
    const double sigma = StretchSpectrum(deformation_gradient(el.beta, gather(e, x))).sigma1;
    // Held: a face still beyond its own limit that the solve, with the barrier acting (gap to
    // the raised limit under ŝ), brought down by less than a quarter of that gap: a load holds
    // it against the barrier.
    const double gap = el.limit - el.fitted_stretch;
    const bool held = after == FitAfter::solve && el.limit > el.own_limit &&
                      sigma >= el.own_limit && gap < band_ &&
                      el.fitted_stretch - sigma < 0.25 * gap;
    const double lowered =
        el.limit > sigma ? sigma + 0.5 * (el.limit - sigma) : sigma + 0.5 * band_;
    // A held face gets the gap ŝ/2 back instead of half its gap: a log barrier's Newton step is
    // of the gap's size, so halving the gap of a face that does not move would shrink its steps
    // below the Newton tolerance for good.
    const double next = held ? sigma + 0.5 * band_ : lowered;
    el.limit = std::max(el.own_limit, next);
    el.fitted_stretch = sigma;
    if (el.limit <= el.own_limit)
      el.scale = 1.0;
    else if (held)
      el.scale = std::min(el.scale * kHeldScaleGrowth, kMaxHeldScale);
    raised += el.limit > el.own_limit;
  }
  return raised;
}

void StrainLimit::set_stiffness(double stiffness) {
  if (!(stiffness > 0.0) || !std::isfinite(stiffness))
    fail(Status::invalid_argument,
         "strain_limit: stiffness must be > 0 (got " + std::to_string(stiffness) + ")");
  stiffness_ = stiffness;
}

double StrainLimit::max_stretch(const Vector& x) const {
  if (x.size() != 3 * static_cast<Eigen::Index>(num_vertices_))
    fail(Status::invalid_argument, "strain_limit: max_stretch of " + std::to_string(x.size()) +
                                       " DOFs for " + std::to_string(num_vertices_) + " vertices");
  double stretch = 0.0;
#pragma omp parallel for reduction(max        \
                                   : stretch) \
    schedule(static) if (num_elements() >= kMinParallelItems)
  for (int e = 0; e < num_elements(); ++e)
    stretch = std::max(
        stretch, StretchSpectrum(deformation_gradient(elements_[e].beta, gather(e, x))).sigma1);
  return stretch;
}

double StrainLimit::element_value(int e, const LocalVector& xe) const {
  const double limit = elements_[e].limit;
  const StretchSpectrum spectrum(deformation_gradient(elements_[e].beta, xe));
  const double d1 = limit - spectrum.sigma1, d2 = limit - spectrum.sigma2;
  if (d1 >= band_) return 0.0;        // both below the activation s − ŝ
  if (!(d1 > 0.0)) return kInfinity;  // at or beyond the limit (or non-finite)
  double sum = Barrier(d1, band_).value;
  if (d2 < band_) sum += Barrier(d2, band_).value;
  return stiffness_ * elements_[e].weight() * sum;
}

namespace {

/// g', g'' and the divided difference of g' at the singular values (both d_i > 0, d₁ < ŝ).
SpectralDerivatives spectral_derivatives(const StretchSpectrum& spectrum, double limit,
                                         double band) {
  SpectralDerivatives out{};
  const double sigma[2] = {spectrum.sigma1, spectrum.sigma2};
  for (int i = 0; i < 2; ++i) {
    const double d = limit - sigma[i];
    if (d >= band) continue;  // inactive: g ≡ 0 near λ_i (g is C² at the activation)
    const Barrier h(d, band);
    const double s = sigma[i];  // > s − ŝ > 1
    out.g1[i] = h.slope / (2.0 * s);
    out.g2[i] = (h.curvature - h.slope / s) / (4.0 * s * s);
  }
  const double gap = sigma[0] - sigma[1];  // ≥ 0
  const double scale = std::min(limit - sigma[0], limit - sigma[1]);
  if (gap > kIsotropicRatio * scale)
    out.divided = (out.g1[0] - out.g1[1]) / (gap * (sigma[0] + sigma[1]));
  else
    out.divided = 0.5 * (out.g2[0] + out.g2[1]);  // → g''(λ) as λ₁ − λ₂ → 0
  return out;
}

}  // namespace

void StrainLimit::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  const Element& el = elements_[e];
  const Mat32 f = deformation_gradient(elements_[e].beta, xe);
  const StretchSpectrum spectrum(f);
  const double d1 = el.limit - spectrum.sigma1;
  if (d1 >= band_) {
    g.setZero();
    return;
  }
  if (!(d1 > 0.0)) {
    g.setConstant(kNaN);  // infinite energy: no meaningful force (see class comment)
    return;
  }
  const SpectralDerivatives sd = spectral_derivatives(spectrum, el.limit, band_);
  // ∂Φ/∂C = S = Σ_i g'(λ_i) v_i v_iᵀ (Lewis 1996); dΦ = ⟨S, dFᵀF + FᵀdF⟩ = ⟨2FS, dF⟩, and
  // ∂E/∂x_a = κĀ (∂Φ/∂F) β_a.
  const Mat2 s = sd.g1[0] * spectrum.v1 * spectrum.v1.transpose() +
                 sd.g1[1] * spectrum.v2 * spectrum.v2.transpose();
  const Mat32 p = (2.0 * stiffness_ * el.weight()) * (f * s);
  for (int a = 0; a < 3; ++a) g.segment<3>(3 * a) = p * el.beta.row(a).transpose();
}

void StrainLimit::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  const Element& el = elements_[e];
  const Mat32 f = deformation_gradient(elements_[e].beta, xe);
  const StretchSpectrum spectrum(f);
  const double d1 = el.limit - spectrum.sigma1;
  if (d1 >= band_) {
    h.setZero();
    return;
  }
  if (!(d1 > 0.0)) {
    h.setConstant(kNaN);
    return;
  }
  const SpectralDerivatives sd = spectral_derivatives(spectrum, el.limit, band_);
  const double w = stiffness_ * el.weight();
  const Vec2& v1 = spectrum.v1;
  const Vec2& v2 = spectrum.v2;
  // d²Φ[dC, dC] = Σ_i g''(λ_i)(v_iᵀ dC v_i)² + 2 δ (v₁ᵀ dC v₂)²  (Daleckii–Krein /
  // Lewis & Sendov 2001), δ the divided difference; plus ⟨S, d²C⟩ with d²C = 2 dFᵀdF.
  // With dF = Σ_a dx_a β_aᵀ: v_iᵀ dC v_j = Σ_a dx_a · [(β_a·v_j) F v_i + (β_a·v_i) F v_j], and
  // ⟨S, dFᵀdF⟩ = Σ_ab (β_aᵀ S β_b) dx_a·dx_b.
  const Vec3 fv1 = f * v1, fv2 = f * v2;
  LocalVector q1, q2, q12;
  for (int a = 0; a < 3; ++a) {
    const Vec2 beta = el.beta.row(a).transpose();
    const double b1 = beta.dot(v1), b2 = beta.dot(v2);
    q1.segment<3>(3 * a) = (2.0 * b1) * fv1;
    q2.segment<3>(3 * a) = (2.0 * b2) * fv2;
    q12.segment<3>(3 * a) = b2 * fv1 + b1 * fv2;
  }
  const Mat2 s = sd.g1[0] * v1 * v1.transpose() + sd.g1[1] * v2 * v2.transpose();
  const Mat3 bsb = el.beta * s * el.beta.transpose();  // β_aᵀ S β_b
  h.noalias() = (w * sd.g2[0]) * q1 * q1.transpose();
  h.noalias() += (w * sd.g2[1]) * q2 * q2.transpose();
  h.noalias() += (2.0 * w * sd.divided) * q12 * q12.transpose();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      h.block<3, 3>(3 * a, 3 * b).diagonal().array() += 2.0 * w * bsb(a, b);
}

void StrainLimit::element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  // In the basis u_k v_jᵀ, n̂ v_jᵀ of F-space (F = U Σ Vᵀ, n̂ the normal) the F-Hessian has the
  // eigenvalues h''(σ_i) ≥ 0 (u_i v_iᵀ), 2g'(λ_j) ≥ 0 (n̂ v_jᵀ) and those of
  // 2[[δσ₁² + g'(λ₂), δσ₁σ₂], [δσ₁σ₂, δσ₂² + g'(λ₁)]] with δ ≥ 0 (g' is non-decreasing) on
  // u₁v₂ᵀ, u₂v₁ᵀ: all ≥ 0, so the exact Hessian needs no projection.
  element_hessian(e, xe, h);
}

}  // namespace progsim
