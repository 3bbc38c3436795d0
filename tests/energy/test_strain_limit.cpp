// Strain-limiting barrier: derivatives against finite differences in the active band
// (anisotropic, exactly isotropic, sheared and near-limit states), the switch to g'' at σ₁ = σ₂,
// exact zeros below the band, +∞ at and beyond the limit, the closed-form energy, per-face
// limits, rigid-motion invariance, PSD Hessians, max_stretch and argument checks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "energy/strain_limit.hpp"
#include "mesh/mesh_generators.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;
using pt::eigenvalues;
using pt::rigidly_moved;

namespace {

constexpr double kLimit = 1.06;
constexpr double kBand = 0.04;  // the barrier acts for σ > 1.02
constexpr double kStiffness = 1e3;
constexpr double kEdge = 1.0 / 3.0;  // grid_mesh() edge length

TriangleMesh grid_mesh() {
  return make_grid(1.0, 1.0, 3, 3);
}

/// b(d, d̂) = −(d − d̂)² ln(d/d̂) on (0, d̂), 0 beyond: the reference energy, written out.
double barrier(double d, double band) {
  if (d >= band) return 0.0;
  return -(d - band) * (d - band) * std::log(d / band);
}

/// Every vertex p mapped to A p (A acts in the x–y plane of the grid and may lift it).
Positions mapped(const Positions& p, const Mat3& a) {
  Positions out(p.rows(), 3);
  for (Eigen::Index v = 0; v < p.rows(); ++v) out.row(v) = (a * p.row(v).transpose()).transpose();
  return out;
}

/// Rotation by angle θ about z.
Mat3 rotation_z(double angle) {
  Mat3 r;
  r << std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle), 0, 0, 0, 1;
  return r;
}

/// In-plane stretch by σ₁ along direction θ and σ₂ across it: singular values (σ₁, σ₂) for
/// every face of a flat mesh in the x–y plane.
Mat3 stretch(double sigma1, double sigma2, double angle) {
  const Mat3 r = rotation_z(angle);
  return r * Vec3(sigma1, sigma2, 1.0).asDiagonal() * r.transpose();
}

/// The DOFs of p moved by a random rigid motion and perturbed by uniform noise.
Vector posed(const Positions& p, unsigned seed, double noise) {
  return rigidly_moved(pt::perturbed(p, noise, seed), pt::random_rotation(seed + 100),
                       Vec3(0.2, -0.7, 1.1));
}

/// The term's derivatives at x against finite differences, x inside the limit's active band.
void expect_active_derivatives_match(const EnergyTerm& term, const Vector& x, double step,
                                     double tolerance) {
  ASSERT_GT(term.value(x), 0.0) << "state is not in the active band";
  pt::expect_derivatives_match_finite_differences(term, x, step, tolerance);
}

/// A single triangle with rest edges D̄ = [[1, 0.3], [0, 0.8]] in the x–y plane.
struct Triangle {
  Positions rest;
  Faces faces;
  Mat2 rest_edges;
  Triangle() : rest(3, 3), faces(1, 3) {
    rest << 0, 0, 0, 1, 0, 0, 0.3, 0.8, 0;
    faces << 0, 1, 2;
    rest_edges << 1, 0.3, 0, 0.8;
  }
  /// Positions whose deformation gradient is f (3×2), placed at x0.
  Vector deformed(const Eigen::Matrix<double, 3, 2>& f, const Vec3& x0) const {
    const Eigen::Matrix<double, 3, 2> d = f * rest_edges;
    Vector x(9);
    x << x0, x0 + d.col(0), x0 + d.col(1);
    return x;
  }
};

/// F = U diag(σ₁, σ₂) Vᵀ with random orthonormal U (3×2) and rotation V.
Eigen::Matrix<double, 3, 2> random_deformation_gradient(double sigma1, double sigma2,
                                                        std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(0.0, kTwoPi);
  const Mat3 u = pt::random_rotation(static_cast<unsigned>(rng()));
  const double t = angle(rng);
  Mat2 v;
  v << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  return u.leftCols<2>() * Vec2(sigma1, sigma2).asDiagonal() * v.transpose();
}

}  // namespace

TEST(StrainLimit, DerivativesMatchFiniteDifferencesInTheActiveBand) {
  const TriangleMesh mesh = grid_mesh();
  // Limits differ from face to face (activation at 1.02, 1.03, 1.04), so a mix-up shows.
  std::vector<double> limits(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) limits[f] = kLimit + 0.01 * (f % 3);
  const StrainLimit varied(mesh.vertices, mesh.faces, limits, kBand, kStiffness);
  const StrainLimit uniform(mesh.vertices, mesh.faces,
                            std::vector<double>(mesh.num_faces(), kLimit), kBand, kStiffness);
  EXPECT_STREQ(varied.name(), "strain_limit");
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.075;  // σ ≈ (1.038, 0.963): one active, one inactive singular value
  Mat3 sheared_stretch;
  sheared_stretch << 1.035, 0.02, 0, -0.01, 1.03, 0, 0, 0, 1;
  struct State {
    const char* what;
    const StrainLimit* term;
    Mat3 map;
    double noise;  ///< × edge
  };
  const State states[] = {
      {"anisotropic, one σ active", &varied, stretch(1.05, 1.0, 0.5), 1e-3},
      {"anisotropic, both σ active", &varied, stretch(1.05, 1.045, -0.3), 1e-3},
      {"exactly isotropic, mid band", &uniform,
       stretch(kLimit - 0.5 * kBand, kLimit - 0.5 * kBand, 0), 0.0},
      {"isotropic, near the limit", &uniform, stretch(kLimit - 1e-3, kLimit - 1e-3, 0), 0.0},
      {"isotropic, just above the activation", &uniform,
       stretch(kLimit - kBand + 1e-3, kLimit - kBand + 1e-3, 0), 0.0},
      {"pure shear", &uniform, shear, 0.0},
      {"shear and stretch", &varied, sheared_stretch, 1e-3},
  };
  unsigned seed = 1;
  for (const State& s : states) {
    SCOPED_TRACE(s.what);
    const Positions p = mapped(mesh.vertices, s.map);
    // Unmoved (for the isotropic states: σ₁ = σ₂ up to rounding) and rigidly posed in 3D.
    expect_active_derivatives_match(*s.term, as_dofs(p), 1e-6 * kEdge, 1e-5);
    expect_active_derivatives_match(*s.term, posed(p, seed++, s.noise * kEdge), 1e-6 * kEdge, 1e-5);
  }
}

TEST(StrainLimit, RandomSingleTriangleStatesMatchFiniteDifferencesAndArePsd) {
  // F = U diag(σ) Vᵀ with random U, V and σ anywhere from inactive to 2e-4 below the limit,
  // with a share of exactly and nearly equal singular values.
  const Triangle tri;
  const StrainLimit term(tri.rest, tri.faces, {kLimit}, kBand, kStiffness);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    SCOPED_TRACE(trial);
    const double sigma1 = kLimit - kBand + (kBand - 2e-4) * unit(rng);
    double sigma2 = 0.9 + (sigma1 - 0.9) * unit(rng);
    if (trial % 4 == 0) sigma2 = sigma1;
    if (trial % 4 == 1) sigma2 = sigma1 * (1.0 - std::pow(10.0, -3.0 - 9.0 * unit(rng)));
    const Eigen::Matrix<double, 3, 2> f = random_deformation_gradient(sigma1, sigma2, rng);
    const Vector x = tri.deformed(f, Vec3(unit(rng), unit(rng), unit(rng)));
    EXPECT_NEAR(term.max_stretch(x), sigma1, 1e-12);
    expect_active_derivatives_match(term, x, 1e-7, 1e-5);
    const Eigen::MatrixXd h = pt::assembled_hessian(term, x, false);
    const Eigen::VectorXd lambda = eigenvalues(h);
    EXPECT_GE(lambda.minCoeff(), -1e-10 * lambda.maxCoeff()) << "exact Hessian not PSD";
    EXPECT_EQ(pt::assembled_hessian(term, x, true), h);
  }
}

TEST(StrainLimit, HessianIsContinuousAcrossTheIsotropicSwitch) {
  // σ = σ̄ ± ε around an isotropic state in the band: the divided difference of g' gives way to
  // g'' when 2ε < 1e-5 · (s − σ₁). The Hessian must stay continuous in ε through the switch and
  // match finite differences on both sides.
  const Triangle tri;
  const StrainLimit term(tri.rest, tri.faces, {kLimit}, kBand, kStiffness);
  const double mean = kLimit - 0.5 * kBand;
  std::mt19937 rng(3);
  const Eigen::Matrix<double, 3, 2> base = random_deformation_gradient(1.0, 1.0, rng);
  const auto state = [&](double eps) {
    Eigen::Matrix<double, 3, 2> f = base;
    f.col(0) *= mean + eps;
    f.col(1) *= mean - eps;
    return tri.deformed(f, Vec3(0.1, 0.2, 0.3));
  };
  const Eigen::MatrixXd h0 = pt::assembled_hessian(term, state(0.0), false);
  ASSERT_TRUE(h0.allFinite());
  const double d = kLimit - mean;
  for (double eps : {1e-14, 1e-12, 1e-10, 5e-8, 1e-7, 2e-7, 1e-6, 1e-5}) {
    SCOPED_TRACE(eps);
    const Vector x = state(eps);
    const Eigen::MatrixXd h = pt::assembled_hessian(term, x, false);
    // ∂H/∂ε is O(H/d): allow 20 ε/d plus rounding.
    EXPECT_LT(pt::relative_error(h, h0, 1e-12), 1e-10 + 20.0 * eps / d);
    expect_active_derivatives_match(term, x, 1e-7, 1e-6);
  }
}

TEST(StrainLimit, ExactlyZeroBelowTheBand) {
  const TriangleMesh mesh = grid_mesh();
  const StrainLimit term(mesh.vertices, mesh.faces, std::vector<double>(mesh.num_faces(), kLimit),
                         kBand, kStiffness);
  const double below = kLimit - kBand - 1e-3;
  for (const Mat3& map : {Mat3(Mat3::Identity()), stretch(below, below, 0.0),
                          stretch(below, 0.5, 0.7), stretch(0.3, 0.2, 0.1)}) {
    const Vector x = posed(mapped(mesh.vertices, map), 5, 0.0);
    EXPECT_EQ(term.value(x), 0.0);
    EXPECT_TRUE((pt::analytic_gradient(term, x).array() == 0.0).all());
    EXPECT_TRUE((pt::assembled_hessian(term, x, false).array() == 0.0).all());
    EXPECT_TRUE((pt::assembled_hessian(term, x, true).array() == 0.0).all());
  }
}

TEST(StrainLimit, PerFaceLimitsDecideWhichFacesAreActive) {
  // A uniform stretch σ = 1.035: faces with limit 1.05 (active above 1.01) resist, faces with
  // limit 1.08 (active above 1.04) do not; E = Σ_active Ā κ · 2 b(s − σ, ŝ).
  const TriangleMesh mesh = grid_mesh();
  std::vector<double> limits(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) limits[f] = (f % 3 == 0) ? 1.05 : 1.08;
  const StrainLimit term(mesh.vertices, mesh.faces, limits, kBand, kStiffness);
  const double sigma = 1.035;
  const Vector x = posed(mapped(mesh.vertices, stretch(sigma, sigma, 0.0)), 9, 0.0);
  double expected = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    EXPECT_EQ(term.limit(f), limits[f]);
    EXPECT_NEAR(term.rest_area(f), 1.0 / 18.0, 1e-15);
    expected += term.rest_area(f) * kStiffness * 2.0 * barrier(limits[f] - sigma, kBand);
  }
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(term.value(x), expected, 1e-9 * expected);
  // Vertices touched only by inactive faces feel no force.
  const Vector g = pt::analytic_gradient(term, x);
  std::vector<bool> touched(mesh.num_vertices(), false);
  for (int f = 0; f < mesh.num_faces(); f += 3)
    for (int k = 0; k < 3; ++k) touched[mesh.faces(f, k)] = true;
  int untouched = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (!touched[v]) {
      ++untouched;
      EXPECT_EQ(g.segment<3>(3 * v).norm(), 0.0) << "vertex " << v;
    }
  EXPECT_GE(untouched, 4);
}

TEST(StrainLimit, ClosedFormEnergyGrowsWithoutBoundTowardsTheLimit) {
  // A right triangle with legs 1 and 0.5, rigidly posed in 3D, stretched by σ₁ along its x leg
  // and σ₂ along its y leg: E = Ā κ (b(s − σ₁) + b(s − σ₂)).
  const double limit = 1.25, band = 0.125;  // exactly representable: σ = s is hit exactly
  Positions rest(3, 3);
  rest << 0, 0, 0, 1, 0, 0, 0, 0.5, 0;
  Faces faces(1, 3);
  faces << 0, 1, 2;
  const Mat3 r = pt::random_rotation(21);
  const Vec3 t(0.1, 0.2, -0.3);
  const StrainLimit term(rest, faces, {limit}, band, 2.0);
  EXPECT_EQ(term.band(), band);
  EXPECT_NEAR(term.rest_area(0), 0.25, 1e-15);
  const auto at = [&](double sigma1, double sigma2) {
    return rigidly_moved(as_dofs(mapped(rest, stretch(sigma1, sigma2, 0.0))), r, t);
  };
  double previous = 0.0;
  for (double d : {0.1, 0.05, 1e-2, 1e-4, 1e-7, 1e-10}) {
    SCOPED_TRACE(d);
    const double sigma = limit - d;
    const double e = term.value(at(sigma, sigma));
    const double expected = 0.25 * 2.0 * 2.0 * barrier(d, band);
    EXPECT_NEAR(e, expected, 1e-6 * expected);
    EXPECT_GT(e, previous);
    previous = e;
    const double e_aniso = term.value(at(sigma, 1.15));
    EXPECT_NEAR(e_aniso, 0.25 * 2.0 * (barrier(d, band) + barrier(0.1, band)), 1e-6 * e);
  }
  // −(d − d̂)² ln(d/d̂) → ∞ as d → 0, if slowly.
  EXPECT_GT(previous, 0.25 * 2.0 * 2.0 * band * band * 18.0);
  // At and beyond the limit: +∞ energy, NaN derivatives.
  // Unposed, σ = s exactly (F = diag(σ₁, σ₂) without rounding); posed, just beyond.
  const auto unposed = [&](double sigma1, double sigma2) {
    return Vector(as_dofs(mapped(rest, stretch(sigma1, sigma2, 0.0))));
  };
  for (const Vector& x : {unposed(limit, limit), unposed(limit, 1.0), unposed(1.0, limit),
                          at(limit + 1e-12, 1.0), at(1.3, 1.1), at(3.0, 3.0)}) {
    EXPECT_EQ(term.value(x), std::numeric_limits<double>::infinity());
    EXPECT_TRUE(pt::analytic_gradient(term, x).array().isNaN().all());
    EXPECT_TRUE(pt::assembled_hessian(term, x, true).array().isNaN().all());
  }
  // One over-stretched face makes the whole term infinite.
  const TriangleMesh mesh = grid_mesh();
  const StrainLimit grid_term(mesh.vertices, mesh.faces,
                              std::vector<double>(mesh.num_faces(), kLimit), kBand, kStiffness);
  Positions pulled = mesh.vertices;
  EXPECT_EQ(grid_term.value(as_dofs(pulled)), 0.0);
  pulled(5, 0) += 0.2 * kEdge;
  EXPECT_EQ(grid_term.value(as_dofs(pulled)), std::numeric_limits<double>::infinity());
}

TEST(StrainLimit, InvariantUnderRigidMotion) {
  const TriangleMesh mesh = grid_mesh();
  const StrainLimit term(mesh.vertices, mesh.faces, std::vector<double>(mesh.num_faces(), kLimit),
                         kBand, kStiffness);
  const Vector x = pt::perturbed(mapped(mesh.vertices, stretch(1.045, 1.03, 0.4)), 2e-3 * kEdge, 4);
  ASSERT_GT(term.value(x), 0.0);
  const Mat3 r = pt::random_rotation(12);
  const Vec3 t(0.3, -1.7, 2.2);
  const Vector y = rigidly_moved(x, r, t);
  EXPECT_NEAR(term.value(y), term.value(x), 1e-11 * term.value(x));
  const Vector gx = pt::analytic_gradient(term, x), gy = pt::analytic_gradient(term, y);
  EXPECT_LT(pt::relative_error(gy, rigidly_moved(gx, r, Vec3::Zero()), 1e-12), 1e-9);
  // Rigid translations are in the Hessian's null space.
  const Eigen::MatrixXd h = pt::assembled_hessian(term, y, false);
  for (int k = 0; k < 3; ++k) {
    Vector translation = Vector::Zero(x.size());
    for (int v = 0; v < mesh.num_vertices(); ++v) translation[3 * v + k] = 1.0;
    EXPECT_LT((h * translation).norm(), 1e-10 * h.norm());
  }
}

TEST(StrainLimit, AssembledHessianIsPsdAndProjectionKeepsIt) {
  const TriangleMesh mesh = grid_mesh();
  const StrainLimit term(mesh.vertices, mesh.faces, std::vector<double>(mesh.num_faces(), kLimit),
                         kBand, kStiffness);
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    const Vector x =
        posed(mapped(mesh.vertices, stretch(1.045, 1.035, 0.3 * seed)), seed, 4e-3 * kEdge);
    const Eigen::MatrixXd exact = pt::assembled_hessian(term, x, false);
    const Eigen::MatrixXd projected = pt::assembled_hessian(term, x, true);
    const Eigen::VectorXd lambda = eigenvalues(projected);
    EXPECT_GT(lambda.maxCoeff(), 0.0);
    EXPECT_GE(lambda.minCoeff(), -1e-10 * lambda.maxCoeff());
    EXPECT_EQ(projected, exact);
  }
}

TEST(StrainLimit, MaxStretchAndStiffness) {
  const TriangleMesh mesh = grid_mesh();
  StrainLimit term(mesh.vertices, mesh.faces, std::vector<double>(mesh.num_faces(), kLimit), kBand,
                   kStiffness);
  EXPECT_NEAR(term.max_stretch(as_dofs(mesh.vertices)), 1.0, 1e-14);
  EXPECT_NEAR(term.max_stretch(posed(mapped(mesh.vertices, stretch(1.3, 0.9, 0.6)), 2, 0.0)), 1.3,
              1e-12);
  EXPECT_NEAR(term.max_stretch(posed(mapped(mesh.vertices, stretch(0.8, 1.1, -0.2)), 3, 0.0)), 1.1,
              1e-12);
  EXPECT_THROW(term.max_stretch(Vector::Zero(6)), Error);
  // E is linear in κ.
  const Vector x = posed(mapped(mesh.vertices, stretch(1.05, 1.0, 0.2)), 4, 0.0);
  const double e = term.value(x);
  EXPECT_EQ(term.stiffness(), kStiffness);
  term.set_stiffness(3.0 * kStiffness);
  EXPECT_EQ(term.stiffness(), 3.0 * kStiffness);
  EXPECT_NEAR(term.value(x), 3.0 * e, 1e-12 * e);
  for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(term.set_stiffness(bad), Error) << bad;
  EXPECT_EQ(term.stiffness(), 3.0 * kStiffness);
}

TEST(StrainLimit, LargeMeshTakesTheParallelPathsConsistently) {
  // 3200 faces (≥ kMinParallelItems): OpenMP value, gradient and max_stretch reductions.
  const TriangleMesh mesh = make_grid(1.0, 1.0, 40, 40);
  const StrainLimit term(mesh.vertices, mesh.faces, std::vector<double>(mesh.num_faces(), kLimit),
                         kBand, kStiffness);
  const double sigma1 = 1.05, sigma2 = 1.03;
  const Vector x = posed(mapped(mesh.vertices, stretch(sigma1, sigma2, 0.25)), 8, 0.0);
  EXPECT_NEAR(term.max_stretch(x), sigma1, 1e-12);
  const double expected =
      kStiffness * (barrier(kLimit - sigma1, kBand) + barrier(kLimit - sigma2, kBand));  // Σ Ā = 1
  EXPECT_NEAR(term.value(x), expected, 1e-9 * expected);
  // Interior forces cancel under a homogeneous stretch; the total force is zero.
  const Vector g = pt::analytic_gradient(term, x);
  Vec3 total = Vec3::Zero();
  for (int v = 0; v < mesh.num_vertices(); ++v) total += g.segment<3>(3 * v);
  EXPECT_LT(total.norm(), 1e-10 * g.cwiseAbs().maxCoeff());
  const int interior = 20 * 41 + 20;  // vertex (20, 20)
  EXPECT_LT(g.segment<3>(3 * interior).norm(), 1e-10 * g.cwiseAbs().maxCoeff());
  EXPECT_GT(g.cwiseAbs().maxCoeff(), 0.0);
}

TEST(StrainLimit, RejectsBadArguments) {
  const TriangleMesh mesh = make_grid(1.0, 1.0, 2, 2);
  const int n = mesh.num_faces();
  const std::vector<double> limits(n, kLimit);
  const auto status_of = [](auto&& make) {
    try {
      make();
    } catch (const Error& e) {
      return e.status();
    }
    return Status::ok;
  };
  const auto make = [&](const Positions& rest, const Faces& faces, std::vector<double> l,
                        double band, double stiffness) {
    return [=] { StrainLimit(rest, faces, l, band, stiffness); };
  };
  const Positions& v = mesh.vertices;
  const Faces& f = mesh.faces;
  EXPECT_EQ(status_of(make(v, f, limits, kBand, kStiffness)), Status::ok);
  EXPECT_EQ(status_of(make(v, f, std::vector<double>(n - 1, kLimit), kBand, kStiffness)),
            Status::invalid_argument);
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  for (double bad_limit : {1.0, 0.9, -2.0, nan, inf}) {
    std::vector<double> l = limits;
    l[n - 1] = bad_limit;
    EXPECT_EQ(status_of(make(v, f, l, 0.01, kStiffness)), Status::invalid_argument) << bad_limit;
  }
  for (double bad_band : {0.0, -0.01, kLimit - 1.0, 0.1, nan, inf})
    EXPECT_EQ(status_of(make(v, f, limits, bad_band, kStiffness)), Status::invalid_argument)
        << bad_band;
  std::vector<double> one_tight = limits;
  one_tight[2] = 1.03;  // band 0.04 ≥ 1.03 − 1 for this face only
  EXPECT_EQ(status_of(make(v, f, one_tight, kBand, kStiffness)), Status::invalid_argument);
  EXPECT_EQ(status_of(make(v, f, one_tight, 0.029, kStiffness)), Status::ok);
  for (double bad_stiffness : {0.0, -1.0, nan, inf})
    EXPECT_EQ(status_of(make(v, f, limits, kBand, bad_stiffness)), Status::invalid_argument)
        << bad_stiffness;
  Positions degenerate = v;
  degenerate.row(f(0, 2)) = degenerate.row(f(0, 0));
  EXPECT_EQ(status_of(make(degenerate, f, limits, kBand, kStiffness)), Status::invalid_mesh);
  Faces out_of_range = f;
  out_of_range(1, 1) = mesh.num_vertices();
  EXPECT_EQ(status_of(make(v, out_of_range, limits, kBand, kStiffness)), Status::invalid_mesh);
  out_of_range(1, 1) = -1;
  EXPECT_EQ(status_of(make(v, out_of_range, limits, kBand, kStiffness)), Status::invalid_mesh);
}

TEST(StrainLimit, FitLimitsRaisesTheLimitOfAnOverstretchedFaceAndBringsItBack) {
  const Triangle t;  // F = diag(σ₁, 1) stretches it to σ₁ = its first singular value
  const Positions& rest = t.rest;
  const Faces& faces = t.faces;
  StrainLimit term(rest, faces, {kLimit}, kBand, kStiffness);
  const Vector beyond = as_dofs(mapped(rest, stretch(1.2, 1.0, 0.0)));  // σ₁ = 1.2 > 1.06
  EXPECT_EQ(term.value(beyond), std::numeric_limits<double>::infinity());
  EXPECT_EQ(term.fit_limits(beyond), 1);
  EXPECT_NEAR(term.limit(0), 1.2 + 0.5 * kBand, 1e-12);  // in the band: the barrier pulls back
  EXPECT_TRUE(std::isfinite(term.value(beyond)));
  EXPECT_GT(term.value(beyond), 0.0);
  // Relaxed to σ₁ = 1.1 the limit comes halfway down (1.22 → 1.16); at σ₁ = 1.0 it returns
  // to the face's own 1.06 after a few calls, and the face's energy is its own again.
  const Vector relaxed = as_dofs(mapped(rest, stretch(1.1, 1.0, 0.0)));
  EXPECT_EQ(term.fit_limits(relaxed), 1);
  EXPECT_NEAR(term.limit(0), 1.1 + 0.5 * (1.2 + 0.5 * kBand - 1.1), 1e-12);
  const Vector within = as_dofs(mapped(rest, stretch(1.0, 1.0, 0.0)));
  int raised = 1;
  for (int k = 0; k < 10 && raised > 0; ++k) raised = term.fit_limits(within);
  EXPECT_EQ(raised, 0);
  EXPECT_EQ(term.limit(0), kLimit);
  EXPECT_EQ(term.value(beyond), std::numeric_limits<double>::infinity());
}

TEST(StrainLimit, FitLimitsStiffensTheBarrierOfAFaceALoadHoldsAndResetsIt) {
  const Triangle t;  // F = diag(σ₁, 1) stretches it to σ₁ = its first singular value
  const Positions& rest = t.rest;
  const Faces& faces = t.faces;
  StrainLimit term(rest, faces, {kLimit}, kBand, kStiffness);
  const auto at = [&](double sigma1) { return as_dofs(mapped(rest, stretch(sigma1, 1.0, 0.0))); };
  ASSERT_EQ(term.fit_limits(at(1.2)), 1);  // raised: the barrier starts at scale 1
  EXPECT_EQ(term.barrier_scale(0), 1.0);
  // A face that came down by at least a quarter of its gap to the limit (ŝ/2 here) is moving.
  ASSERT_EQ(term.fit_limits(at(1.2 - 0.3 * kBand)), 1);
  EXPECT_EQ(term.barrier_scale(0), 1.0);
  // Held where it was: each fit stiffens its barrier fourfold and sets the limit ŝ/2 above the
  // face (a log barrier's Newton step is of the gap's size).
  const double held = 1.2 - 0.3 * kBand;
  for (double expected : {4.0, 16.0, 64.0}) {
    ASSERT_EQ(term.fit_limits(at(held)), 1);
    EXPECT_EQ(term.barrier_scale(0), expected);
    EXPECT_DOUBLE_EQ(term.limit(0), held + 0.5 * kBand);
  }
  // The energy is the barrier of a face with that limit and κ × scale.
  StrainLimit reference(rest, faces, {term.limit(0)}, kBand, 64.0 * kStiffness);
  const Vector x = at(held);
  EXPECT_NEAR(term.value(x), reference.value(x), 1e-12 * reference.value(x));
  EXPECT_LT(pt::relative_error(pt::analytic_gradient(term, x), pt::analytic_gradient(reference, x),
                               1e-12),
            1e-12);
  EXPECT_LT(pt::relative_error(pt::assembled_hessian(term, x, false),
                               pt::assembled_hessian(reference, x, false), 1e-12),
            1e-12);
  // Prescribed motion moves faces by itself: a fit after it judges no face held.
  ASSERT_EQ(term.fit_limits(x, StrainLimit::FitAfter::motion), 1);
  EXPECT_EQ(term.barrier_scale(0), 64.0);
  // Back under its own limit: the scale returns to 1.
  int raised = 1;
  for (int k = 0; k < 10 && raised > 0; ++k) raised = term.fit_limits(at(1.0));
  EXPECT_EQ(raised, 0);
  EXPECT_EQ(term.barrier_scale(0), 1.0);
}
