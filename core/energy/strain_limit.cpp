#include "energy/strain_limit.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "energy/spectral_stretch.hpp"

namespace progsim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Growth of a held face's barrier stiffness per fit_limits call, and its cap.
constexpr double kHeldScaleGrowth = 4.0;
constexpr double kMaxHeldScale = 1e12;

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

}  // namespace

StrainLimit::StrainLimit(const Positions& rest, const Faces& faces, std::vector<double> face_limits,
                         double band, double stiffness)
    : StencilTerm<3>(triangle_stencils(faces, rest.rows(), "strain_limit"),
                     static_cast<int>(rest.rows())),
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
#pragma omp parallel for reduction(+ : raised) schedule(static) num_threads(loop_threads(num_elements()))
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

void StrainLimit::check_size(const Vector& x, const char* what) const {
  if (x.size() != 3 * static_cast<Eigen::Index>(num_vertices_))
    fail(Status::invalid_argument, std::string("strain_limit: ") + what + " of " +
                                       std::to_string(x.size()) + " DOFs for " +
                                       std::to_string(num_vertices_) + " vertices");
}

double StrainLimit::max_stretch(const Vector& x) const {
  check_size(x, "max_stretch");
  double stretch = 0.0;
#pragma omp parallel for reduction(max                         \
                                   : stretch) schedule(static) \
    num_threads(loop_threads(num_elements()))
  for (int e = 0; e < num_elements(); ++e)
    stretch = std::max(
        stretch, StretchSpectrum(deformation_gradient(elements_[e].beta, gather(e, x))).sigma1);
  return stretch;
}

std::vector<int> StrainLimit::faces_beyond_limit(const Vector& x) const {
  check_size(x, "faces_beyond_limit");
  std::vector<int> beyond;
  for (int e = 0; e < num_elements(); ++e)
    if (StretchSpectrum(deformation_gradient(elements_[e].beta, gather(e, x))).sigma1 >=
        elements_[e].own_limit)
      beyond.push_back(e);
  return beyond;
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

/// g', g'' and the divided difference of g' at the singular values (d₁ = s − σ₁ ∈ (0, ŝ)).
SpectralDerivatives spectral_derivatives(const StretchSpectrum& spectrum, double limit,
                                         double band) {
  const double sigma[2] = {spectrum.sigma1, spectrum.sigma2};
  StretchDerivatives h[2];
  for (int i = 0; i < 2; ++i) {
    const double d = limit - sigma[i];
    if (d >= band) continue;  // inactive: h ≡ 0 near σ_i (b is C² at the activation)
    const Barrier b(d, band);
    h[i] = {b.slope, b.curvature};
  }
  return SpectralDerivatives(spectrum, h, limit - sigma[0]);
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
  // ∂E/∂x = κĀ ∂Φ/∂x (Lewis 1996).
  g = spectral_gradient(f, spectrum, spectral_derivatives(spectrum, el.limit, band_), el.beta,
                        stiffness_ * el.weight());
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
  h = spectral_hessian(f, spectrum, spectral_derivatives(spectrum, el.limit, band_), el.beta,
                       stiffness_ * el.weight());
}

void StrainLimit::element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  // In the basis u_k v_jᵀ, n̂ v_jᵀ of F-space (F = U Σ Vᵀ, n̂ the normal) the F-Hessian has the
  // eigenvalues h''(σ_i) ≥ 0 (u_i v_iᵀ), 2g'(λ_j) ≥ 0 (n̂ v_jᵀ) and those of
  // 2[[δσ₁² + g'(λ₂), δσ₁σ₂], [δσ₁σ₂, δσ₂² + g'(λ₁)]] with δ ≥ 0 (g' is non-decreasing) on
  // u₁v₂ᵀ, u₂v₁ᵀ: all ≥ 0, so the exact Hessian needs no projection.
  element_hessian(e, xe, h);
}

}  // namespace progsim
