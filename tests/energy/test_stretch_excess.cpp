// Stretch-excess penalty (the strain-limit correction's objective, PSQ §4.4.5): the energy
// against the closed form with singular values from Eigen's SVD, derivatives against finite
// differences (one or both singular values beyond the target, an exactly isotropic stretch),
// exact zeros below the target, PSD Hessians (so the exact Hessian serves as its projection),
// and argument checks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "common/error.hpp"
#include "energy/stretch_excess.hpp"
#include "mesh/mesh_generators.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;

namespace stretch_excess_test {
namespace {

constexpr double kTarget = 1.05;
constexpr double kStiffness = 7.0;

TriangleMesh grid_mesh() {
  return make_grid(1.0, 1.0, 3, 3);
}

/// Every vertex p of the flat grid mapped to A p.
Vector mapped(const Positions& p, const Mat3& a) {
  Positions out(p.rows(), 3);
  for (Eigen::Index v = 0; v < p.rows(); ++v) out.row(v) = (a * p.row(v).transpose()).transpose();
  return as_dofs(out);
}

/// ρ Σ_f Ā_f Σ_i (σ_i − t_f)₊², with σ_i from Eigen's SVD (membrane_singular_values).
double reference_energy(const TriangleMesh& rest, const Vector& x,
                        const std::vector<double>& targets, double stiffness) {
  double sum = 0.0;
  for (int f = 0; f < rest.num_faces(); ++f) {
    const Vec2 sigma = pt::membrane_singular_values(rest.vertices, rest.faces, x, f);
    for (int i = 0; i < 2; ++i) {
      const double excess = std::max(0.0, sigma[i] - targets[f]);
      sum += stiffness * face_areas(rest.vertices, rest.faces)[f] * excess * excess;
    }
  }
  return sum;
}

Mat3 stretch(double sx, double sy, double shear) {
  Mat3 a = Mat3::Identity();
  a(0, 0) = sx;
  a(1, 1) = sy;
  a(0, 1) = shear;
  a(2, 0) = 0.1;  // lifts the sheet out of its plane
  return a;
}

}  // namespace

TEST(StretchExcess, EnergyEqualsTheClosedFormWithSvdSingularValues) {
  const TriangleMesh mesh = grid_mesh();
  std::vector<double> targets(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) targets[f] = kTarget + 0.02 * (f % 3);
  const StretchExcess term(mesh.vertices, mesh.faces, targets, kStiffness);
  EXPECT_STREQ(term.name(), "stretch_excess");
  for (const Mat3& a : {stretch(1.2, 1.0, 0.0), stretch(1.3, 1.15, 0.05), stretch(1.1, 1.1, 0.0)}) {
    const Vector x =
        pt::rigidly_moved(mapped(mesh.vertices, a), pt::random_rotation(3u), Vec3(0.3, -0.2, 0.5));
    const double expected = reference_energy(mesh, x, targets, kStiffness);
    ASSERT_GT(expected, 0.0);
    EXPECT_NEAR(term.value(x), expected, 1e-12 * expected);
  }
}

TEST(StretchExcess, DerivativesMatchFiniteDifferences) {
  const TriangleMesh mesh = grid_mesh();
  const StretchExcess term(mesh.vertices, mesh.faces,
                           std::vector<double>(mesh.num_faces(), kTarget), kStiffness);
  struct State {
    const char* what;
    Vector x;
  };
  const State states[] = {
      {"σ₁ beyond, σ₂ below", mapped(mesh.vertices, stretch(1.25, 0.95, 0.02))},
      {"both beyond", mapped(mesh.vertices, stretch(1.3, 1.12, 0.04))},
      {"noisy",
       pt::perturbed(Positions(as_positions(mapped(mesh.vertices, stretch(1.2, 1.0, 0.0)))), 0.02,
                     11u)},
  };
  for (const State& s : states) {
    SCOPED_TRACE(s.what);
    ASSERT_GT(term.value(s.x), 0.0);
    pt::expect_derivatives_match_finite_differences(term, s.x, 1e-6, 1e-5);
  }
}

TEST(StretchExcess, IsotropicStretchHasFiniteDerivativesMatchingFiniteDifferences) {
  // σ₁ = σ₂ exactly: the divided difference is replaced by the mean of g''.
  const TriangleMesh mesh = grid_mesh();
  const StretchExcess term(mesh.vertices, mesh.faces,
                           std::vector<double>(mesh.num_faces(), kTarget), kStiffness);
  const Vector x = mapped(mesh.vertices, 1.2 * Mat3::Identity());
  pt::expect_derivatives_match_finite_differences(term, x, 1e-6, 1e-5);
}

TEST(StretchExcess, ExactlyZeroBelowTheTargets) {
  const TriangleMesh mesh = grid_mesh();
  const StretchExcess term(mesh.vertices, mesh.faces,
                           std::vector<double>(mesh.num_faces(), kTarget), kStiffness);
  const Vector x = pt::rigidly_moved(mapped(mesh.vertices, stretch(1.04, 0.7, 0.0)),
                                     pt::random_rotation(5u), Vec3(1, 2, 3));
  EXPECT_EQ(term.value(x), 0.0);
  EXPECT_EQ(pt::analytic_gradient(term, x).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(pt::assembled_hessian(term, x, false).cwiseAbs().maxCoeff(), 0.0);
}

TEST(StretchExcess, HessianIsPsd) {
  const TriangleMesh mesh = grid_mesh();
  const StretchExcess term(mesh.vertices, mesh.faces,
                           std::vector<double>(mesh.num_faces(), kTarget), kStiffness);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Vector x = pt::perturbed(
        Positions(as_positions(mapped(mesh.vertices, stretch(1.2, 1.1, 0.1)))), 0.05, seed);
    const Eigen::MatrixXd h = pt::assembled_hessian(term, x, false);
    const double scale = h.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    EXPECT_GT(pt::eigenvalues(h).minCoeff(), -1e-10 * scale) << "seed " << seed;
  }
}

TEST(StretchExcess, RejectsBadArguments) {
  const TriangleMesh mesh = grid_mesh();
  const std::vector<double> targets(mesh.num_faces(), kTarget);
  const auto status_of = [&](auto make) {
    try {
      make();
    } catch (const Error& e) {
      return e.status();
    }
    return Status::ok;
  };
  EXPECT_EQ(status_of([&] { StretchExcess(mesh.vertices, mesh.faces, {1.1}, 1.0); }),
            Status::invalid_argument);
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    std::vector<double> t = targets;
    t[2] = bad;
    EXPECT_EQ(status_of([&] { StretchExcess(mesh.vertices, mesh.faces, t, 1.0); }),
              Status::invalid_argument);
    EXPECT_EQ(status_of([&] { StretchExcess(mesh.vertices, mesh.faces, targets, bad); }),
              Status::invalid_argument);
  }
  Faces faces = mesh.faces;
  faces(1, 2) = static_cast<int>(mesh.vertices.rows());
  EXPECT_EQ(status_of([&] { StretchExcess(mesh.vertices, faces, targets, 1.0); }),
            Status::invalid_mesh);
  StretchExcess term(mesh.vertices, mesh.faces, targets, 1.0);
  EXPECT_EQ(status_of([&] { term.set_stiffness(0.0); }), Status::invalid_argument);
  term.set_stiffness(3.0);
  EXPECT_EQ(term.stiffness(), 3.0);
}

}  // namespace stretch_excess_test
