// Tension-field membrane: derivatives against finite differences in each of its three states,
// its energy against the relaxation it stands for (the neo-Hookean membrane minimized over the
// lengths wrinkles may take up, searched numerically) plus its share ε of the full energy, PSD
// projection, and a face collapsed to a segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "common/error.hpp"
#include "energy/neo_hookean_membrane.hpp"
#include "energy/tension_field_membrane.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;

namespace {

/// One triangle in the x–y plane with edge 0→1 along x, so that the rest frame's coordinates
/// are x and y and a state x_a = A X_a has deformation gradient A.
struct OneTriangle {
  Positions rest;
  Faces faces;
  ShellMaterial material;

  explicit OneTriangle(double poisson_ratio) : rest(3, 3), faces(1, 3) {
    rest << 0, 0, 0, 1, 0, 0, 0.3, 0.8, 0;
    faces << 0, 1, 2;
    material.poisson_ratio = poisson_ratio;
  }
  /// The state whose deformation gradient has singular values s1, s2, turned by `seed` (0: not
  /// turned, F = diag(s1, s2) exactly).
  Vector state(double s1, double s2, unsigned seed) const {
    const double angle = 0.37 * seed;
    Mat2 v;
    v << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    Mat32 a = Mat32::Zero();
    a(0, 0) = s1;
    a(1, 1) = s2;
    if (seed > 0) a = pt::random_rotation(seed) * a * v.transpose();
    Positions x(3, 3);
    for (int i = 0; i < 3; ++i) x.row(i) = (a * rest.row(i).head<2>().transpose()).transpose();
    return as_dofs(x);
  }
};

/// Minimum of f over [lo, hi] by golden-section search (f unimodal there).
double golden_minimum(const std::function<double(double)>& f, double lo, double hi) {
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi;
  for (int k = 0; k < 200 && b - a > 1e-13; ++k) {
    const double c = b - r * (b - a), d = a + r * (b - a);
    if (f(c) < f(d))
      b = d;
    else
      a = c;
  }
  return f(0.5 * (a + b));
}

}  // namespace

TEST(TensionFieldMembrane, DerivativesMatchFiniteDifferencesInEveryState) {
  // (σ₁, σ₂): wrinkled, wrinkled near collapse, taut, slack, for four Poisson ratios (ν = 0:
  // uniaxial tension keeps σ₂* = 1; ν < 0: σ₂* > 1).
  const double states[][2] = {{1.3, 0.7}, {2.0, 0.5}, {1.4, 1e-2}, {1.2, 1.1}, {0.9, 0.6}};
  for (double nu : {-0.3, 0.0, 0.3, 0.45})
    for (double share : {0.0, TensionFieldMembrane::kDefaultCompressionShare}) {
      const OneTriangle t(nu);
      const TensionFieldMembrane term(t.rest, t.faces, {t.material}, share);
      for (const auto& s : states)
        for (unsigned seed : {1u, 2u}) {
          SCOPED_TRACE("nu " + std::to_string(nu) + ", share " + std::to_string(share) +
                       ", stretches " + std::to_string(s[0]) + ", " + std::to_string(s[1]) +
                       ", seed " + std::to_string(seed));
          pt::expect_derivatives_match_finite_differences(term, t.state(s[0], s[1], seed), 1e-6,
                                                          1e-6);
        }
    }
}

TEST(TensionFieldMembrane, EnergyIsTheNeoHookeanMinimumOverLongerPrincipalStretches) {
  // Pipkin's relaxation: W(σ₁, σ₂) = min over σ₁' ≥ σ₁, σ₂' ≥ σ₂ of the neo-Hookean energy,
  // searched here through NeoHookeanMembrane's value alone (nested golden sections); with the
  // share ε of the full energy Ψ, W_ε = (1 − ε) W + ε Ψ.
  const OneTriangle t(0.3);
  const TensionFieldMembrane relaxed(t.rest, t.faces, {t.material}, 0.0);
  const double eps = 0.01;
  const TensionFieldMembrane shared(t.rest, t.faces, {t.material}, eps);
  const NeoHookeanMembrane full(t.rest, t.faces, {t.material});
  const auto minimum = [&](double s1, double s2) {
    return golden_minimum(
        [&](double a) {
          return golden_minimum([&](double b) { return full.value(t.state(a, b, 3)); }, s2,
                                s2 + 2.0);
        },
        s1, s1 + 2.0);
  };
  const double scale = full.value(t.state(1.3, 1.0, 3));
  const double states[][2] = {{1.3, 0.7}, {2.0, 0.5}, {1.05, 0.9}, {1.2, 1.1}, {0.9, 0.6}};
  for (const auto& s : states) {
    SCOPED_TRACE(std::to_string(s[0]) + ", " + std::to_string(s[1]));
    const double w = relaxed.value(t.state(s[0], s[1], 3));
    const double psi = full.value(t.state(s[0], s[1], 3));
    EXPECT_NEAR(w, minimum(s[0], s[1]), 1e-9 * scale);
    EXPECT_LE(w, psi + 1e-12 * scale);
    EXPECT_NEAR(shared.value(t.state(s[0], s[1], 3)), (1.0 - eps) * w + eps * psi, 1e-12 * scale);
  }
  // Taut: the two energies agree exactly; slack: no energy.
  EXPECT_EQ(relaxed.value(t.state(1.2, 1.1, 4)), full.value(t.state(1.2, 1.1, 4)));
  EXPECT_EQ(relaxed.value(t.state(0.9, 0.6, 4)), 0.0);
  EXPECT_GT(full.value(t.state(0.9, 0.6, 4)), 0.0);
}

TEST(TensionFieldMembrane, ProjectedHessianIsPsdAndExactWhereTheHessianIsPsd) {
  // With ε = 0 a wrinkled face's exact Hessian is PSD (g'' > 0, g' > 0), so its projection must
  // be the exact Hessian; with ε > 0 the share of Ψ adds the indefinite compressed modes.
  const OneTriangle t(0.3);
  const NeoHookeanMembrane full(t.rest, t.faces, {t.material});
  for (double share : {0.0, TensionFieldMembrane::kDefaultCompressionShare}) {
    const TensionFieldMembrane term(t.rest, t.faces, {t.material}, share);
    int wrinkled_compared = 0;
    for (unsigned seed = 1; seed <= 20; ++seed) {
      SCOPED_TRACE("share " + std::to_string(share) + ", seed " + std::to_string(seed));
      const double s1 = 0.6 + 0.1 * seed, s2 = 0.05 * seed;
      const Vector x = t.state(std::max(s1, s2), std::min(s1, s2), seed);
      const Eigen::MatrixXd exact = pt::assembled_hessian(term, x, false);
      const Eigen::MatrixXd projected = pt::assembled_hessian(term, x, true);
      const double largest = std::max(1.0, pt::eigenvalues(exact).cwiseAbs().maxCoeff());
      EXPECT_GE(pt::eigenvalues(projected).minCoeff(), -1e-9 * largest);
      if (pt::eigenvalues(exact).minCoeff() < -1e-9 * largest) continue;
      EXPECT_LT(pt::relative_error(projected, exact, 1e-12), 1e-9);
      const double w = term.value(x);
      wrinkled_compared += w > 0.0 && w < full.value(x);
    }
    if (share == 0.0) EXPECT_GT(wrinkled_compared, 3);
  }
}

TEST(TensionFieldMembrane, AFaceCollapsedToASegmentHasFiniteEnergyOnlyWithoutTheFullShare) {
  // The neo-Hookean membrane gives such a face +∞ energy; wrinkles can take up any shortening,
  // but the share ε of Ψ keeps the barrier that stops a face collapsing.
  const OneTriangle t(0.3);
  const TensionFieldMembrane relaxed(t.rest, t.faces, {t.material}, 0.0);
  const TensionFieldMembrane shared(t.rest, t.faces, {t.material});
  const NeoHookeanMembrane full(t.rest, t.faces, {t.material});
  for (double s1 : {1.5, 0.5}) {
    const Vector x = t.state(s1, 0.0, 0);
    EXPECT_TRUE(std::isinf(full.value(x)));
    EXPECT_TRUE(std::isinf(shared.value(x)));
    EXPECT_TRUE(std::isfinite(relaxed.value(x)));
    EXPECT_TRUE(pt::analytic_gradient(relaxed, x).allFinite());
    EXPECT_TRUE(pt::assembled_hessian(relaxed, x, true).allFinite());
    EXPECT_EQ(relaxed.value(x) > 0.0, s1 > 1.0);  // wrinkled under tension, slack otherwise
  }
}

TEST(TensionFieldMembrane, EnergyAndForceAreContinuousWhereAWrinkledFaceTurnsTaut) {
  // σ₂* at σ₁ = 1.3, ν = 0.3 lies in (0.9, 0.95): step σ₂ across it in small increments.
  const OneTriangle t(0.3);
  const TensionFieldMembrane term(t.rest, t.faces, {t.material});
  const NeoHookeanMembrane full(t.rest, t.faces, {t.material});
  ASSERT_LT(term.value(t.state(1.3, 0.9, 6)), full.value(t.state(1.3, 0.9, 6)));    // wrinkled
  ASSERT_EQ(term.value(t.state(1.3, 0.95, 6)), full.value(t.state(1.3, 0.95, 6)));  // taut
  const double h = 1e-4;
  double largest_jump = 0.0, force_scale = 0.0;
  for (double s2 = 0.9; s2 < 0.95; s2 += h) {
    const Vector g0 = pt::analytic_gradient(term, t.state(1.3, s2, 6));
    const Vector g1 = pt::analytic_gradient(term, t.state(1.3, s2 + h, 6));
    largest_jump = std::max(largest_jump, (g1 - g0).cwiseAbs().maxCoeff());
    force_scale = std::max(force_scale, g0.cwiseAbs().maxCoeff());
  }
  // A C¹ energy changes its force by O(h) per step; a jump in the force would be O(1).
  EXPECT_LT(largest_jump, 100.0 * h * force_scale);
}

TEST(TensionFieldMembrane, RejectsACompressionShareOutsideZeroToOne) {
  const OneTriangle t(0.3);
  for (double share : {-0.1, 1.0, std::nan("")})
    EXPECT_THROW(TensionFieldMembrane(t.rest, t.faces, {t.material}, share), Error);
}
