#include "energy/stretch_excess.hpp"

#include <cmath>
#include <string>

#include "common/error.hpp"
#include "energy/spectral_stretch.hpp"

namespace progsim {
namespace {

/// h(σ) = (σ − t)₊² per singular value, with h' = 2(σ − t)₊ and h'' = 2 [σ > t].
SpectralDerivatives excess_derivatives(const StretchSpectrum& spectrum, double target) {
  const double sigma[2] = {spectrum.sigma1, spectrum.sigma2};
  StretchDerivatives h[2];
  for (int i = 0; i < 2; ++i)
    if (sigma[i] > target) h[i] = {2.0 * (sigma[i] - target), 2.0};
  return SpectralDerivatives(spectrum, h, spectrum.sigma1);
}

}  // namespace

StretchExcess::StretchExcess(const Positions& rest, const Faces& faces, std::vector<double> targets,
                             double stiffness)
    : StencilTerm<3>(triangle_stencils(faces, rest.rows(), "stretch_excess"),
                     static_cast<int>(rest.rows())) {
  if (targets.size() != static_cast<std::size_t>(faces.rows()))
    fail(Status::invalid_argument, "stretch_excess: " + std::to_string(targets.size()) +
                                       " targets for " + std::to_string(faces.rows()) + " faces");
  set_stiffness(stiffness);
  elements_.resize(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (!(targets[f] > 0.0) || !std::isfinite(targets[f]))
      fail(Status::invalid_argument, "stretch_excess: target of face " + std::to_string(f) +
                                         " must be > 0 (got " + std::to_string(targets[f]) + ")");
    const TriangleFrame frame = rest_triangle_frame(rest, faces, f, "stretch_excess");
    elements_[f] = {frame.beta, frame.area, targets[f]};
  }
}

void StretchExcess::set_stiffness(double stiffness) {
  if (!(stiffness > 0.0) || !std::isfinite(stiffness))
    fail(Status::invalid_argument,
         "stretch_excess: stiffness must be > 0 (got " + std::to_string(stiffness) + ")");
  stiffness_ = stiffness;
}

double StretchExcess::element_value(int e, const LocalVector& xe) const {
  const Element& el = elements_[e];
  const StretchSpectrum spectrum(deformation_gradient(el.beta, xe));
  double sum = 0.0;
  for (const double sigma : {spectrum.sigma1, spectrum.sigma2})
    if (sigma > el.target) sum += (sigma - el.target) * (sigma - el.target);
  return stiffness_ * el.area * sum;  // ρ Ā Σ_i (σ_i − t)₊²
}

void StretchExcess::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  const Element& el = elements_[e];
  const Mat32 f = deformation_gradient(el.beta, xe);
  const StretchSpectrum spectrum(f);
  if (!(spectrum.sigma1 > el.target)) {
    g.setZero();
    return;
  }
  g = spectral_gradient(f, spectrum, excess_derivatives(spectrum, el.target), el.beta,
                        stiffness_ * el.area);
}

void StretchExcess::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  const Element& el = elements_[e];
  const Mat32 f = deformation_gradient(el.beta, xe);
  const StretchSpectrum spectrum(f);
  if (!(spectrum.sigma1 > el.target)) {
    h.setZero();
    return;
  }
  h = spectral_hessian(f, spectrum, excess_derivatives(spectrum, el.target), el.beta,
                       stiffness_ * el.area);
}

void StretchExcess::element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  element_hessian(e, xe, h);  // convex in F (see the class comment)
}

}  // namespace progsim
