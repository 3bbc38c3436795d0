// Neo-Hookean membrane: derivatives against finite differences, zero force at flat and curved
// rest shapes, rigid-motion invariance, PSD projection, the closed-form energy of a uniaxial
// stretch, and the +∞ energy of a degenerate triangle.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "common/error.hpp"
#include "energy/neo_hookean_membrane.hpp"
#include "mesh/mesh_generators.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;
using pt::eigenvalues;
using pt::expect_derivatives_match_finite_differences;
using pt::perturbed;
using pt::rigidly_moved;
using pt::varied_materials;

namespace {

struct MembraneMesh {
  TriangleMesh mesh;
  double edge;  ///< typical edge length (m)
};

MembraneMesh grid_case() {
  return {make_grid(1.0, 1.0, 3, 3), 1.0 / 3.0};
}
MembraneMesh cylinder_case() {
  return {make_cylinder(0.4, 0.6, 2.0, 4, 3), 0.2};
}

}  // namespace

TEST(NeoHookeanMembrane, DerivativesMatchFiniteDifferencesAtRandomStates) {
  for (const MembraneMesh& c : {grid_case(), cylinder_case()}) {
    const NeoHookeanMembrane term(c.mesh.vertices, c.mesh.faces,
                                  varied_materials(c.mesh.num_faces(), 3));
    EXPECT_STREQ(term.name(), "membrane");
    for (unsigned seed : {1u, 2u, 3u}) {
      SCOPED_TRACE(seed);
      const Vector x = perturbed(c.mesh.vertices, 0.25 * c.edge, seed);
      expect_derivatives_match_finite_differences(term, x, 1e-6 * c.edge, 1e-6);
    }
  }
}

TEST(NeoHookeanMembrane, LargeStretchAndCompressionDerivativesMatchFiniteDifferences) {
  const MembraneMesh c = grid_case();
  const NeoHookeanMembrane term(c.mesh.vertices, c.mesh.faces,
                                varied_materials(c.mesh.num_faces(), 4));
  for (double scale : {0.4, 2.5}) {
    SCOPED_TRACE(scale);
    const Vector x = scale * perturbed(c.mesh.vertices, 0.2 * c.edge, 9);
    expect_derivatives_match_finite_differences(term, x, 1e-6 * c.edge, 1e-6);
  }
}

TEST(NeoHookeanMembrane, RestShapeHasZeroEnergyAndForce) {
  const TriangleMesh sphere = make_sphere(0.3, 1);
  for (const TriangleMesh& mesh : {grid_case().mesh, cylinder_case().mesh, sphere}) {
    const std::vector<ShellMaterial> materials = varied_materials(mesh.num_faces(), 5);
    const NeoHookeanMembrane term(mesh.vertices, mesh.faces, materials);
    const Vector x = as_dofs(mesh.vertices);
    // Force scale μ t ℓ ~ 1e6 · 1e-3 · 0.3 N; rounding leaves ~1e-16 of it.
    EXPECT_LT(pt::analytic_gradient(term, x).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_NEAR(term.value(x), 0.0, 1e-11);
  }
}

TEST(NeoHookeanMembrane, InvariantUnderRigidMotion) {
  const MembraneMesh c = cylinder_case();
  const NeoHookeanMembrane term(c.mesh.vertices, c.mesh.faces,
                                varied_materials(c.mesh.num_faces(), 6));
  const Vector x = perturbed(c.mesh.vertices, 0.25 * c.edge, 11);
  const Mat3 r = pt::random_rotation(12);
  const Vec3 t(0.3, -1.7, 2.2);
  const Vector y = rigidly_moved(x, r, t);
  EXPECT_NEAR(term.value(y), term.value(x), 1e-12 * std::abs(term.value(x)));
  const Vector gx = pt::analytic_gradient(term, x), gy = pt::analytic_gradient(term, y);
  EXPECT_LT(pt::relative_error(gy, rigidly_moved(gx, r, Vec3::Zero()), 1e-12), 1e-10);
}

TEST(NeoHookeanMembrane, ProjectedHessianIsPsdAndExactWhereNothingNeedsClamping) {
  const MembraneMesh c = grid_case();
  const NeoHookeanMembrane term(c.mesh.vertices, c.mesh.faces,
                                varied_materials(c.mesh.num_faces(), 7));
  // Compressed: the exact Hessian is indefinite, the projected one PSD.
  const Vector compressed = 0.7 * perturbed(c.mesh.vertices, 0.2 * c.edge, 13);
  const Eigen::VectorXd exact = eigenvalues(pt::assembled_hessian(term, compressed, false));
  const Eigen::VectorXd projected = eigenvalues(pt::assembled_hessian(term, compressed, true));
  EXPECT_LT(exact.minCoeff(), -1e-3 * exact.maxCoeff()) << "state should be indefinite";
  EXPECT_GE(projected.minCoeff(), -1e-8 * projected.maxCoeff());
  // Stretched in-plane by 20% (plus a small perturbation): every element Hessian is PSD, so
  // the projection changes nothing.
  Positions stretched_rest = c.mesh.vertices;
  stretched_rest.leftCols(2) *= 1.2;
  const Vector stretched = perturbed(stretched_rest, 0.01 * c.edge, 14);
  const Eigen::MatrixXd h = pt::assembled_hessian(term, stretched, false);
  EXPECT_GE(eigenvalues(h).minCoeff(), -1e-8 * eigenvalues(h).maxCoeff());
  EXPECT_LT(pt::relative_error(pt::assembled_hessian(term, stretched, true), h, 1e-12), 1e-12);
}

TEST(NeoHookeanMembrane, ProjectionIsTheEigenvalueClampInDeformationGradientSpace) {
  // One triangle with its rest in the x–y plane, edge 0→1 along x, so that F = D D̄⁻¹ with D̄
  // the rest edges' x, y coordinates. The term's projection must equal t Ā Bᵀ clamp(H_F) B,
  // where H_F (6×6) is recovered here from the exact Hessian through B = ∂vec F/∂x (6×9)
  // and the clamp is a plain numerical eigen-decomposition.
  Positions rest(3, 3);
  rest << 0, 0, 0, 1, 0, 0, 0.3, 0.8, 0;
  Faces faces(1, 3);
  faces << 0, 1, 2;
  ShellMaterial m;
  m.poisson_ratio = 0.4;
  const NeoHookeanMembrane term(rest, faces, {m});
  Mat2 rest_edges;
  rest_edges << 1, 0.3, 0, 0.8;
  const Mat2 inverse = rest_edges.inverse();
  Eigen::Matrix<double, 3, 2> beta;
  beta.row(1) = inverse.row(0);
  beta.row(2) = inverse.row(1);
  beta.row(0) = -beta.row(1) - beta.row(2);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(6, 9);  // vec F (column-major) from x
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 2; ++j) b(i + 3 * j, 3 * a + i) = beta(a, j);
  const double weight = m.thickness * term.rest_area(0);
  const Eigen::MatrixXd bbt_inverse = (b * b.transpose()).inverse();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int clamped_states = 0;
  // Compressed, sheared, stretched, isotropically squeezed (σ₁ = σ₂) and sliver states.
  for (int trial = 0; trial < 40; ++trial) {
    SCOPED_TRACE(trial);
    Positions current = rest;
    if (trial == 0) current *= 0.5;                    // σ₁ = σ₂ < 1
    if (trial == 1) current.row(2) << 0.5, 1e-4, 0.0;  // sliver
    if (trial > 1) {
      const double scale = 0.3 + 1.5 * (trial % 7) / 6.0;
      for (int v = 0; v < 3; ++v)
        for (int k = 0; k < 3; ++k) current(v, k) = scale * current(v, k) + 0.3 * unit(rng);
    }
    const Vector x = as_dofs(current);
    const Eigen::MatrixXd exact = pt::assembled_hessian(term, x, false);
    const Eigen::MatrixXd h_f = bbt_inverse * b * exact * b.transpose() * bbt_inverse / weight;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(h_f);
    if (eig.eigenvalues().minCoeff() < 0.0) ++clamped_states;
    const Eigen::MatrixXd reference = weight * b.transpose() * eig.eigenvectors() *
                                      eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
                                      eig.eigenvectors().transpose() * b;
    const Eigen::MatrixXd projected = pt::assembled_hessian(term, x, true);
    EXPECT_LT(pt::relative_error(projected, reference, 1e-300), 1e-8);
    EXPECT_GE(eigenvalues(projected).minCoeff(), -1e-8 * eigenvalues(projected).maxCoeff());
    // Rigid translations stay in the null space.
    for (int k = 0; k < 3; ++k) {
      Vector translation = Vector::Zero(9);
      for (int v = 0; v < 3; ++v) translation[3 * v + k] = 1.0;
      EXPECT_LT((projected * translation).norm(), 1e-10 * projected.norm());
    }
  }
  EXPECT_GT(clamped_states, 10) << "too few states exercised the clamp";
}

TEST(NeoHookeanMembrane, UniaxialStretchMatchesClosedFormEnergy) {
  // A right triangle with legs 1 (x) and 0.5 (y), posed in 3D by a random rigid motion,
  // stretched by s along its x leg: C = diag(s², 1), W = μ/2(s² − 1 − ln s²) + λ/8 (ln s²)².
  ShellMaterial m;
  m.youngs_modulus = 2e6;
  m.poisson_ratio = 0.35;
  m.thickness = 2e-3;
  const Mat3 r = pt::random_rotation(21);
  const Vec3 t(0.1, 0.2, -0.3);
  Positions rest(3, 3);
  rest << 0, 0, 0, 1, 0, 0, 0, 0.5, 0;
  Faces faces(1, 3);
  faces << 0, 1, 2;
  const Positions posed = ((rest * r.transpose()).rowwise() + t.transpose()).eval();
  const NeoHookeanMembrane term(posed, faces, {m});
  EXPECT_NEAR(term.rest_area(0), 0.25, 1e-15);
  const double mu = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
  const double lambda =
      m.youngs_modulus * m.poisson_ratio / (1 - m.poisson_ratio * m.poisson_ratio);
  for (double s : {0.5, 0.9, 1.0, 1.3, 3.0}) {
    Positions current = rest;
    current.col(0) *= s;
    current = ((current * r.transpose()).rowwise() + t.transpose()).eval();
    const double l = std::log(s * s);
    const double w = 0.5 * mu * (s * s - 1 - l) + 0.125 * lambda * l * l;
    EXPECT_NEAR(term.value(as_dofs(current)), m.thickness * 0.25 * w, 1e-12 * (1 + std::abs(w)))
        << "s = " << s;
  }
}

TEST(NeoHookeanMembrane, SmallStrainEnergyKeepsItsRelativePrecision) {
  // Stretch s = 1 + η with η down to 1e-7: W = μ/2 (s² − 1 − ln s²) + λ/8 (ln s²)² is O(η²),
  // evaluated here by its series, s² − 1 − 2 ln s = 2η² − 2η³/3 + η⁴/2 − 2η⁵/5 + ...
  // Forming tr C − 2 − ln det C directly would lose all digits at η = 1e-7.
  ShellMaterial m;
  Positions rest(3, 3);
  rest << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Faces faces(1, 3);
  faces << 0, 1, 2;
  const NeoHookeanMembrane term(rest, faces, {m});
  const double mu = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
  const double lambda =
      m.youngs_modulus * m.poisson_ratio / (1 - m.poisson_ratio * m.poisson_ratio);
  for (double eta : {1e-3, 1e-5, 1e-7, -1e-7}) {
    Positions current = rest;
    current(1, 0) = 1.0 + eta;
    double series = 0.0, power = eta;
    for (int k = 2; k < 12; ++k) {
      power *= eta;
      series += (k % 2 == 0 ? 2.0 : -2.0) * power / k;
    }
    series += eta * eta;  // s² − 1 − 2 log1p(η) = η² + 2 Σ_{k≥2} (−η)^k / k
    const double log_s2 = 2.0 * std::log1p(eta);
    const double w = 0.5 * mu * series + 0.125 * lambda * log_s2 * log_s2;
    EXPECT_NEAR(term.value(as_dofs(current)) / (m.thickness * 0.5 * w), 1.0, 1e-6)
        << "eta = " << eta;
  }
}

TEST(NeoHookeanMembrane, DegenerateTriangleHasInfiniteEnergyAndNaNDerivatives) {
  Positions rest(3, 3);
  rest << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Faces faces(1, 3);
  faces << 0, 1, 2;
  const NeoHookeanMembrane term(rest, faces, std::vector<ShellMaterial>(1));
  Positions collinear = rest;
  collinear.row(2) << 2, 0, 0;  // current area zero: det C = 0
  const Vector x = as_dofs(collinear);
  EXPECT_TRUE(std::isinf(term.value(x)) && term.value(x) > 0.0);
  EXPECT_TRUE(pt::analytic_gradient(term, x).array().isNaN().all());
  EXPECT_TRUE(pt::assembled_hessian(term, x, true).array().isNaN().all());
  Positions collapsed = rest;
  collapsed.setZero();
  EXPECT_TRUE(std::isinf(term.value(as_dofs(collapsed))));
  // A sliver that is still a triangle has a large but finite energy.
  Positions sliver = rest;
  sliver.row(2) << 0.5, 1e-9, 0;
  EXPECT_TRUE(std::isfinite(term.value(as_dofs(sliver))));
  EXPECT_TRUE(pt::analytic_gradient(term, as_dofs(sliver)).allFinite());
}

TEST(NeoHookeanMembrane, RejectsBadInput) {
  const TriangleMesh mesh = make_grid(1.0, 1.0, 2, 2);
  EXPECT_THROW(NeoHookeanMembrane(mesh.vertices, mesh.faces, std::vector<ShellMaterial>(3)), Error);
  Positions degenerate = mesh.vertices;
  degenerate.row(mesh.faces(0, 2)) = degenerate.row(mesh.faces(0, 0));
  try {
    NeoHookeanMembrane(degenerate, mesh.faces, std::vector<ShellMaterial>(mesh.num_faces()));
    ADD_FAILURE() << "no error for a degenerate rest face";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::invalid_mesh);
  }
}
