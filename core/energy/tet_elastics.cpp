#include "energy/tet_elastics.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "energy/positive_volume_step.hpp"
#include "energy/psd_projection.hpp"

namespace progsim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::array<int, 4>> tet_stencils(const Tets& tets, Eigen::Index num_vertices) {
  std::vector<std::array<int, 4>> stencils(tets.rows());
  for (Eigen::Index t = 0; t < tets.rows(); ++t)
    for (int k = 0; k < 4; ++k) {
      const int v = tets(t, k);
      if (v < 0 || v >= num_vertices)
        fail(Status::invalid_mesh, "solid: tet " + std::to_string(t) + " has vertex index " +
                                       std::to_string(v) + " outside [0, " +
                                       std::to_string(num_vertices) + ")");
      stencils[t][k] = v;
    }
  return stencils;
}

void check_material(const SolidMaterial& m, std::size_t t) {
  const bool valid = std::isfinite(m.youngs_modulus) && m.youngs_modulus > 0.0 &&
                     std::isfinite(m.poisson_ratio) && m.poisson_ratio > -1.0 &&
                     m.poisson_ratio < 0.5;
  if (!valid)
    fail(Status::invalid_argument,
         "solid: tet " + std::to_string(t) + " has E = " + std::to_string(m.youngs_modulus) +
             " Pa, nu = " + std::to_string(m.poisson_ratio) + " (need E > 0 and -1 < nu < 0.5)");
}

/// D = [x₁−x₀, x₂−x₀, x₃−x₀] of the stacked tet positions xe (12).
Mat3 edge_matrix(const Eigen::Matrix<double, 12, 1>& xe) {
  Mat3 d;
  for (int k = 0; k < 3; ++k) d.col(k) = xe.segment<3>(3 * (k + 1)) - xe.segment<3>(0);
  return d;
}

}  // namespace

TetElastics::TetElastics(const Positions& rest, const Tets& tets,
                         const std::vector<SolidMaterial>& tet_materials)
    : StencilTerm<4>(tet_stencils(tets, rest.rows()), static_cast<int>(rest.rows())) {
  if (tet_materials.size() != static_cast<std::size_t>(tets.rows()))
    fail(Status::invalid_argument, "solid: " + std::to_string(tet_materials.size()) +
                                       " tet materials for " + std::to_string(tets.rows()) +
                                       " tets");
  elements_.resize(tets.rows());
  for (int t = 0; t < num_elements(); ++t) {
    check_material(tet_materials[t], t);
    LocalVector xe = gather(t, as_dofs(rest));
    const Mat3 d = edge_matrix(xe);
    const double volume = d.determinant() / 6.0;  // V̄ = det D̄ / 6
    if (!(volume > 0.0) || !std::isfinite(volume))
      fail(Status::invalid_mesh, "solid: rest tet " + std::to_string(t) + " has volume " +
                                     std::to_string(volume) + " m^3 (need > 0)");
    Element& el = elements_[t];
    const Mat3 inverse = d.inverse();
    el.beta.bottomRows<3>() = inverse;  // ∂F/∂x_k = D̄⁻¹ row k (k = 1..3)
    el.beta.row(0) = -inverse.colwise().sum();
    el.volume = volume;
    el.lame = lame_parameters(tet_materials[t]);
    el.model = tet_materials[t].model;
  }
}

Mat3 TetElastics::element_deformation_gradient(int e, const LocalVector& xe) const {
  const Element& el = elements_[e];
  Mat3 f = xe.segment<3>(0) * el.beta.row(0);  // F = Σ_a x_a β_aᵀ
  for (int a = 1; a < 4; ++a) f.noalias() += xe.segment<3>(3 * a) * el.beta.row(a);
  return f;
}

Mat3 TetElastics::deformation_gradient(int t, const Vector& x) const {
  return element_deformation_gradient(t, gather(t, x));
}

double TetElastics::element_value(int e, const LocalVector& xe) const {
  const Element& el = elements_[e];
  return el.volume * hyperelastic_density(el.model, el.lame, element_deformation_gradient(e, xe));
}

void TetElastics::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  const Element& el = elements_[e];
  const Mat3 p = first_piola_stress(el.model, el.lame, element_deformation_gradient(e, xe));
  // ∂E/∂x_a = V̄ P β_a
  for (int a = 0; a < 4; ++a) g.segment<3>(3 * a) = el.volume * (p * el.beta.row(a).transpose());
}

void TetElastics::pull_back(int e, const Mat9& d, LocalMatrix& h) const {
  const Element& el = elements_[e];
  // T = d B (9×12) with B mapping x_{b,k} to F_kl by β_bl; then h = V̄ Bᵀ T.
  Eigen::Matrix<double, 9, 12> t;
  for (int b = 0; b < 4; ++b)
    for (int k = 0; k < 3; ++k)
      t.col(3 * b + k) =
          d.col(k) * el.beta(b, 0) + d.col(k + 3) * el.beta(b, 1) + d.col(k + 6) * el.beta(b, 2);
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i)
      h.row(3 * a + i) = el.volume * (el.beta(a, 0) * t.row(i) + el.beta(a, 1) * t.row(i + 3) +
                                      el.beta(a, 2) * t.row(i + 6));
}

void TetElastics::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  const Element& el = elements_[e];
  pull_back(e, stress_derivative(el.model, el.lame, element_deformation_gradient(e, xe)), h);
}

void TetElastics::element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  const Element& el = elements_[e];
  Mat9 d = stress_derivative(el.model, el.lame, element_deformation_gradient(e, xe));
  if (!d.allFinite()) {
    h.setConstant(kNaN);
    return;
  }
  project_psd(d);
  pull_back(e, d, h);
}

double TetElastics::max_step(const Vector& x, const Vector& p) {
  double alpha = 1.0;
  bool finite = true;
#pragma omp parallel for reduction(min : alpha) reduction(&& : finite) schedule(static) num_threads(loop_threads(num_elements()))
  for (int e = 0; e < num_elements(); ++e) {
    const double step = positive_volume_step(edge_matrix(gather(e, x)), edge_matrix(gather(e, p)));
    if (std::isnan(step))
      finite = false;
    else
      alpha = std::min(alpha, step);
  }
  return finite ? alpha : kNaN;
}

}  // namespace progsim
