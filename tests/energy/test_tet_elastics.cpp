// Volumetric hyperelastic tets (neo-Hookean, StVK, fixed corotated): derivatives against finite
// differences, zero force at rest, rigid-motion invariance, the PSD projection, the small-strain
// limit of linear elasticity, the closed-form homogeneous uniaxial stretch solved by Newton,
// and the inversion-free step bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>

#include "common/error.hpp"
#include "energy/positive_volume_step.hpp"
#include "energy/tet_elastics.hpp"
#include "energy/tet_lumped_mass.hpp"
#include "mesh/tet_generators.hpp"
#include "problem/problem.hpp"
#include "solve/newton_solver.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;

namespace {

constexpr std::array<SolidModel, 3> kModels = {SolidModel::neo_hookean, SolidModel::stvk,
                                               SolidModel::corotated};

const char* model_name(SolidModel m) {
  return m == SolidModel::neo_hookean ? "neo_hookean"
         : m == SolidModel::stvk      ? "stvk"
                                      : "corotated";
}

/// The unit cube's 8 corners (vertex i + 2j + 4k at (i, j, k)) split into the 6 tets of the
/// Kuhn subdivision around the diagonal 0–7, each positively oriented.
struct Cube {
  Positions vertices;
  Tets tets;
};

Cube unit_cube() {
  Cube c;
  c.vertices.resize(8, 3);
  for (int v = 0; v < 8; ++v) c.vertices.row(v) << (v & 1), ((v >> 1) & 1), ((v >> 2) & 1);
  std::array<int, 3> axes = {0, 1, 2};
  c.tets.resize(6, 4);
  int t = 0;
  do {
    const int a = 1 << axes[0], b = a + (1 << axes[1]);
    std::array<int, 4> tet = {0, a, b, 7};
    const Vec3 x0 = c.vertices.row(0);
    Mat3 d;
    for (int k = 0; k < 3; ++k) d.col(k) = c.vertices.row(tet[k + 1]).transpose() - x0;
    if (d.determinant() < 0.0) std::swap(tet[2], tet[3]);
    c.tets.row(t++) << tet[0], tet[1], tet[2], tet[3];
  } while (std::next_permutation(axes.begin(), axes.end()));
  return c;
}

std::vector<SolidMaterial> materials(SolidModel model, int n, double e = 1e5, double nu = 0.3) {
  SolidMaterial m;
  m.youngs_modulus = e;
  m.poisson_ratio = nu;
  m.model = model;
  return std::vector<SolidMaterial>(n, m);
}

TetElastics make_term(const Cube& c, SolidModel model, double nu = 0.3) {
  return TetElastics(c.vertices, c.tets, materials(model, 6, 1e5, nu));
}

/// Bisection for the root of a function increasing through zero on [lo, hi].
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  EXPECT_LT(f(lo), 0.0);
  EXPECT_GT(f(hi), 0.0);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Lame {
  double mu, lambda;
};
Lame lame(double e, double nu) {  // Bonet and Wood 2008, eq. 4.32, restated here
  return {e / (2 * (1 + nu)), e * nu / ((1 + nu) * (1 - 2 * nu))};
}

/// Lateral stretch t of F = diag(s, t, t) with zero lateral stress, and the axial P₁₁, from each
/// model's closed-form stress (Bonet and Wood 2008 eqs. 6.11, 6.28; Stomakhin et al. 2012 eq. 5).
std::pair<double, double> uniaxial_reference(SolidModel model, Lame p, double s) {
  if (model == SolidModel::neo_hookean) {
    // t P₂₂ = μ(t² − 1) + λ ln(s t²) = 0
    const double t = bisect(
        [&](double t) { return p.mu * (t * t - 1) + p.lambda * std::log(s * t * t); }, 1e-3, 10.0);
    return {t, p.mu * (s - 1 / s) + p.lambda * std::log(s * t * t) / s};
  }
  if (model == SolidModel::stvk) {
    const double e11 = 0.5 * (s * s - 1);
    const double e22 = -p.lambda * e11 / (2 * (p.mu + p.lambda));  // S₂₂ = 0
    const double t = std::sqrt(1 + 2 * e22);
    return {t, s * (2 * p.mu * e11 + p.lambda * (e11 + 2 * e22))};
  }
  // P₂₂ = 2μ(t − 1) + λ(s t² − 1) s t = 0
  const double t = bisect(
      [&](double t) { return 2 * p.mu * (t - 1) + p.lambda * (s * t * t - 1) * s * t; }, 0.3, 2.0);
  return {t, 2 * p.mu * (s - 1) + p.lambda * (s * t * t - 1) * t * t};
}

/// Stretches the cube to length s along x on symmetry-plane supports (x = 0 fixed in x, y = 0 in
/// y, z = 0 in z, x = 1 face held at x = s) and minimises with Newton. Returns (t, reaction).
std::pair<double, double> solve_uniaxial(SolidModel model, double nu, double s) {
  const Cube c = unit_cube();
  Problem problem(24);
  problem.add_term(std::make_unique<TetElastics>(c.vertices, c.tets, materials(model, 6, 1e5, nu)));
  std::vector<bool> fixed(24, false);
  Vector x = as_dofs(c.vertices);
  for (int v = 0; v < 8; ++v)
    for (int k = 0; k < 3; ++k)
      if (c.vertices(v, k) == 0.0) fixed[3 * v + k] = true;
  for (int v = 0; v < 8; ++v)
    if (c.vertices(v, 0) == 1.0) {
      fixed[3 * v] = true;
      x[3 * v] = s;
    }
  problem.set_fixed_dofs(fixed);
  problem.finalize();
  NewtonSettings settings;
  settings.tolerance = 1e-12;
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, settings, 1.0, 1.0);
  EXPECT_EQ(report.stop, NewtonStop::converged) << model_name(model) << " s = " << s;
  Vector g(24);
  problem.unreduced_gradient(x, g);
  double reaction = 0.0;  // the force the x = 1 face's supports apply, Σ ∂E/∂x over its vertices
  for (int v = 0; v < 8; ++v)
    if (c.vertices(v, 0) == 1.0) reaction += g[3 * v];
  return {x[3 * 7 + 1], reaction};  // vertex 7 = (1, 1, 1): its y is the lateral stretch t
}

}  // namespace

TEST(TetElastics, DerivativesMatchFiniteDifferencesAtRandomStates) {
  const Cube c = unit_cube();
  for (SolidModel model : kModels) {
    SCOPED_TRACE(model_name(model));
    const TetElastics term = make_term(c, model);
    for (unsigned seed : {1u, 2u, 3u}) {
      const Vector x = pt::perturbed(c.vertices, 0.15, seed);
      pt::expect_derivatives_match_finite_differences(term, x, 1e-6, 1e-6);
    }
  }
}

TEST(TetElastics, DerivativesMatchFiniteDifferencesInStrongCompressionAndStretch) {
  const Cube c = unit_cube();
  for (SolidModel model : kModels) {
    SCOPED_TRACE(model_name(model));
    const TetElastics term = make_term(c, model);
    for (const Vec3 scale : {Vec3(0.4, 1.1, 0.9), Vec3(2.5, 0.7, 1.6)}) {
      Positions p = c.vertices * scale.asDiagonal();
      const Vector x = pt::rigidly_moved(pt::perturbed(p, 0.03, 7), pt::random_rotation(5u),
                                         Vec3(0.3, -1.0, 2.0));
      pt::expect_derivatives_match_finite_differences(term, x, 1e-6, 1e-6);
    }
  }
}

TEST(TetElastics, RestAndRigidMotionsHaveNoEnergyNorForce) {
  const Cube c = unit_cube();
  for (SolidModel model : kModels) {
    SCOPED_TRACE(model_name(model));
    const TetElastics term = make_term(c, model);
    for (unsigned seed : {0u, 11u, 12u}) {
      const Vector x = seed == 0 ? Vector(as_dofs(c.vertices))
                                 : pt::rigidly_moved(as_dofs(c.vertices), pt::random_rotation(seed),
                                                     Vec3(1.0, 2.0, -3.0));
      EXPECT_NEAR(term.value(x), 0.0, 1e-9 * 1e5);
      EXPECT_LT(pt::analytic_gradient(term, x).lpNorm<Eigen::Infinity>(), 1e-9 * 1e5);
    }
  }
}

TEST(TetElastics, ProjectedHessianIsPsdAndExactWhereTheExactOneIs) {
  const Cube c = unit_cube();
  for (SolidModel model : kModels) {
    SCOPED_TRACE(model_name(model));
    const TetElastics term = make_term(c, model);
    // At rest every model's Hessian is PSD: projection must not change it.
    const Vector rest = as_dofs(c.vertices);
    const Eigen::MatrixXd exact = pt::assembled_hessian(term, rest, false);
    EXPECT_LT(pt::relative_error(pt::assembled_hessian(term, rest, true), exact, 1e-12), 1e-10);
    // Strong compression makes the exact Hessians indefinite; the projected one stays PSD.
    const Positions squeezed = c.vertices * Vec3(0.3, 0.35, 1.0).asDiagonal();
    const Vector x = pt::perturbed(squeezed, 0.02, 3);
    const Eigen::MatrixXd projected = pt::assembled_hessian(term, x, true);
    EXPECT_GT(pt::eigenvalues(projected).minCoeff(), -1e-9 * projected.cwiseAbs().maxCoeff());
  }
}

TEST(TetElastics, ExactHessiansBecomeIndefiniteUnderCompression) {
  // Guards the previous test against a projection that is never exercised.
  const Cube c = unit_cube();
  for (SolidModel model : {SolidModel::stvk, SolidModel::corotated}) {
    SCOPED_TRACE(model_name(model));
    const TetElastics term = make_term(c, model);
    const Vector x = pt::perturbed(c.vertices * Vec3(0.3, 0.35, 1.0).asDiagonal(), 0.02, 3);
    const Eigen::MatrixXd exact = pt::assembled_hessian(term, x, false);
    EXPECT_LT(pt::eigenvalues(exact).minCoeff(), -1e-6 * exact.cwiseAbs().maxCoeff());
  }
}

TEST(TetElastics, SmallStrainsHaveTheEnergyOfLinearElasticity) {
  // ψ → μ ε:ε + λ/2 (tr ε)² for F = I + εA (every model, Bonet and Wood 2008 §6.4).
  const Cube c = unit_cube();
  Mat3 a;
  a << 0.3, -0.7, 0.2, 0.5, -0.4, 0.9, -0.1, 0.6, 0.8;
  const double eps = 1e-5;
  const Mat3 strain = 0.5 * eps * (a + a.transpose());
  const Lame p = lame(1e5, 0.3);
  const double expected =
      p.mu * strain.squaredNorm() + 0.5 * p.lambda * strain.trace() * strain.trace();
  for (SolidModel model : kModels) {
    SCOPED_TRACE(model_name(model));
    const TetElastics term = make_term(c, model);
    const Positions deformed = c.vertices * (Mat3::Identity() + eps * a).transpose();
    EXPECT_NEAR(term.value(as_dofs(deformed)), expected, 1e-4 * expected);  // unit volume
  }
}

TEST(TetElastics, UniaxialStretchMatchesTheClosedFormLateralStretchAndStress) {
  for (SolidModel model : kModels)
    for (double s : {0.7, 1.3, 2.0}) {
      SCOPED_TRACE(std::string(model_name(model)) + " s = " + std::to_string(s));
      const auto [t_ref, p11_ref] = uniaxial_reference(model, lame(1e5, 0.3), s);
      const auto [t, reaction] = solve_uniaxial(model, 0.3, s);
      EXPECT_NEAR(t, t_ref, 1e-8);
      EXPECT_NEAR(reaction, p11_ref, 1e-6 * std::abs(p11_ref));  // unit reference area
    }
}

TEST(TetElastics, SmallStretchContractsLaterallyByPoissonsRatio) {
  for (SolidModel model : kModels)
    for (double nu : {0.0, 0.25, 0.45}) {
      SCOPED_TRACE(std::string(model_name(model)) + " nu = " + std::to_string(nu));
      const double strain = 1e-4;
      const auto [t, reaction] = solve_uniaxial(model, nu, 1.0 + strain);
      EXPECT_NEAR((t - 1.0) / strain, -nu, 2e-3);
      EXPECT_NEAR(reaction / strain, 1e5, 2e-3 * 1e5);  // Young's modulus
    }
}

TEST(TetElastics, NeoHookeanIsInfiniteForInvertedTets) {
  const Cube c = unit_cube();
  const TetElastics term = make_term(c, SolidModel::neo_hookean);
  Positions flipped = c.vertices;
  flipped.col(2) *= -1.0;  // a mirror: every tet inverted
  EXPECT_EQ(term.value(as_dofs(flipped)), std::numeric_limits<double>::infinity());
}

TEST(TetElastics, MaxStepStopsShortOfInvertingAnyTet) {
  const Cube c = unit_cube();
  for (SolidModel model : kModels) {
    TetElastics term = make_term(c, model);
    const Vector x = as_dofs(c.vertices);
    Vector p = Vector::Zero(24);
    p[3 * 7 + 2] = -4.0;  // vertex 7 dives through the cube: its tets flatten at z = 0, α = 1/4
    const double alpha = term.max_step(x, p);
    EXPECT_NEAR(alpha, 0.8 * 0.25, 1e-9);
    const Vector moved = x + alpha * p;
    for (int t = 0; t < 6; ++t) EXPECT_GT(term.deformation_gradient(t, moved).determinant(), 0.0);
    p[0] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(std::isnan(term.max_step(x, p)));
  }
}

TEST(PositiveVolumeStep, FindsTheFirstRootOfTheVolumeCubic) {
  const Mat3 id = Mat3::Identity();
  EXPECT_EQ(positive_volume_step(id, id), 1.0);                        // growing: no root
  EXPECT_NEAR(positive_volume_step(id, -2.0 * id), 0.8 * 0.5, 1e-12);  // (1 − 2t)³
  // (1 − t/0.3)(1 − t/0.6)(1 + t): negative on (0.3, 0.6), positive again at t = 1.
  const Mat3 dip = Vec3(-1 / 0.3, -1 / 0.6, 1.0).asDiagonal();
  EXPECT_NEAR(positive_volume_step(id, dip), 0.8 * 0.3, 1e-12);
  // A rotation keeps the volume: no bound, though the path is not linear in the rotation.
  Mat3 spin;
  spin << 0, -1, 0, 1, 0, 0, 0, 0, 0;
  const double a = positive_volume_step(id, 1.8 * spin);  // det = 1 + 3.24 t² > 0
  EXPECT_EQ(a, 1.0);
  EXPECT_EQ(positive_volume_step(-id, id), 0.0);  // already inverted
  EXPECT_TRUE(std::isnan(positive_volume_step(id, Mat3::Constant(NAN))));
}

TEST(TetElastics, PassTheLinearPatchTest) {
  // An affine deformation x = A X + b of any tet mesh gives every tet the same F = A, hence the
  // same stress, and the element forces cancel at every interior vertex (the patch test of
  // Irons; Zienkiewicz and Taylor, The Finite Element Method, vol. 1, §9.2).
  const TetMesh box = make_tet_box(Vec3(1.0, 0.8, 0.6), 3, 3, 3);
  Mat3 a;
  a << 1.2, 0.1, -0.05, 0.03, 0.9, 0.2, -0.1, 0.05, 1.1;
  const Positions deformed =
      (box.vertices * a.transpose()).rowwise() + Vec3(0.3, -1, 2).transpose();
  const Vector x = as_dofs(deformed);
  const Vec3 lo = box.vertices.colwise().minCoeff(), hi = box.vertices.colwise().maxCoeff();
  for (SolidModel model : kModels) {
    SCOPED_TRACE(model_name(model));
    const TetElastics term(box.vertices, box.tets, materials(model, box.num_tets()));
    for (int t = 0; t < box.num_tets(); ++t)
      ASSERT_LT((term.deformation_gradient(t, x) - a).norm(), 1e-12) << "tet " << t;
    Vector g = Vector::Zero(x.size());
    term.add_gradient(x, g);
    const double scale = g.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 1e2);  // the deformation is far from rest: boundary forces are large
    int interior = 0;
    for (int v = 0; v < box.num_vertices(); ++v) {
      const Vec3 p = box.vertices.row(v);
      if (((p - lo).array() <= 1e-12).any() || ((hi - p).array() <= 1e-12).any()) continue;
      ++interior;
      EXPECT_LT(g.segment<3>(3 * v).norm(), 1e-12 * scale) << "interior vertex " << v;
    }
    EXPECT_EQ(interior, 8);
    Vec3 net = Vec3::Zero();
    for (int v = 0; v < box.num_vertices(); ++v) net += g.segment<3>(3 * v);
    EXPECT_LT(net.norm(), 1e-12 * scale);  // translation invariance: the forces balance
  }
}

TEST(TetElastics, RejectsBadInputNamingTheProblem) {
  const Cube c = unit_cube();
  Tets inverted = c.tets;
  std::swap(inverted(2, 1), inverted(2, 2));
  try {
    TetElastics(c.vertices, inverted, materials(SolidModel::stvk, 6));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::invalid_mesh);
    EXPECT_NE(std::string(e.what()).find("tet 2"), std::string::npos) << e.what();
  }
  Tets out_of_range = c.tets;
  out_of_range(4, 3) = 8;
  EXPECT_THROW(TetElastics(c.vertices, out_of_range, materials(SolidModel::stvk, 6)), Error);
  EXPECT_THROW(TetElastics(c.vertices, c.tets, materials(SolidModel::stvk, 5)), Error);
  try {
    TetElastics(c.vertices, c.tets, materials(SolidModel::neo_hookean, 6, 1e5, 0.5));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::invalid_argument);
    EXPECT_NE(std::string(e.what()).find("nu"), std::string::npos) << e.what();
  }
}

TEST(TetLumpedMass, QuartersEachTetsMassAmongItsCorners) {
  Cube c = unit_cube();
  c.vertices *= 2.0;  // an 8 m³ cube
  std::vector<SolidMaterial> m = materials(SolidModel::stvk, 6);
  for (int t = 0; t < 6; ++t) m[t].density = 100.0 * (t + 1);  // 1/6 of the volume each
  const Eigen::VectorXd masses = lumped_tet_masses(c.vertices, c.tets, m);
  EXPECT_NEAR(masses.sum(), 8.0 / 6.0 * 100.0 * 21.0, 1e-9);
  // Corners 0 and 7 are in all six tets: a quarter of every tet's mass.
  EXPECT_NEAR(masses[0], 8.0 / 6.0 * 100.0 * 21.0 / 4.0, 1e-9);
  EXPECT_NEAR(masses[7], masses[0], 1e-9);
}
