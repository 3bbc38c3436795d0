// Edge–edge mollifier: threshold from rest edge lengths, the piecewise values (0 for parallel
// edges, 1 beyond the threshold, C¹ across it), derivatives against finite differences.
#include <gtest/gtest.h>

#include "contact/contact_test_support.hpp"
#include "contact/edge_edge_mollifier.hpp"

using namespace progsim;
using namespace progsim::contact_test;

namespace {

/// Edge a = (0,0,0)→(1,0,0), edge b of length 2 at height 0.3 turned by `angle` from a.
Vec12 edges_at_angle(double angle) {
  const Vec3 half(std::cos(angle), std::sin(angle), 0.0);
  return stencil(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, 0.3) - half, Vec3(0.5, 0, 0.3) + half);
}

void expect_derivatives_match(const Vec12& x, double eps_x, double step, double tolerance) {
  double m;
  Vec12 g;
  Mat12 h;
  mollifier_derivatives(x, eps_x, m, g, h);
  EXPECT_EQ(m, mollifier(x, eps_x));
  const auto value = [&](const Vec12& y) { return mollifier(y, eps_x); };
  const auto gradient = [&](const Vec12& y) {
    double my;
    Vec12 gy;
    Mat12 hy;
    mollifier_derivatives(y, eps_x, my, gy, hy);
    return gy;
  };
  EXPECT_LT(relative_error(g, finite_difference_gradient(value, x, step), 1e-8), tolerance)
      << "gradient, x = " << x.transpose();
  Vec12 g_alone;  // the gradient-only path, against the same FD
  EXPECT_EQ(mollifier_gradient(x, eps_x, g_alone), m);
  EXPECT_LT(relative_error(g_alone, finite_difference_gradient(value, x, step), 1e-8), tolerance)
      << "gradient alone, x = " << x.transpose();
  EXPECT_LT(relative_error(h, finite_difference_hessian(gradient, x, step), 1e-8), tolerance)
      << "Hessian, x = " << x.transpose();
  EXPECT_LE((h - h.transpose()).cwiseAbs().maxCoeff(), 1e-12 * h.cwiseAbs().maxCoeff());
}

}  // namespace

TEST(EdgeEdgeMollifier, ThresholdFromRestEdgeLengths) {
  const Vec12 rest = stencil(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(5, 5, 5), Vec3(5, 5, 8));
  EXPECT_NEAR(mollifier_threshold(rest), 1e-3 * 4.0 * 9.0, 1e-16);
}

TEST(EdgeEdgeMollifier, PiecewiseValues) {
  // c = ‖ea × eb‖² = (2 sin θ)², ε_x from the rest state at θ = 0 (‖ēa‖² ‖ēb‖² = 4).
  const double eps_x = mollifier_threshold(edges_at_angle(0.0));
  EXPECT_NEAR(eps_x, 4e-3, 1e-17);
  EXPECT_EQ(mollifier(edges_at_angle(0.0), eps_x), 0.0);
  EXPECT_EQ(mollifier(edges_at_angle(0.5), eps_x), 1.0);
  const double theta = std::asin(std::sqrt(0.5 * eps_x) / 2.0);  // c = ε_x / 2
  EXPECT_NEAR(mollifier(edges_at_angle(theta), eps_x), 0.75, 1e-12);
  // Continuous with a vanishing derivative at c = ε_x.
  const double at = std::asin(std::sqrt(eps_x) / 2.0);
  double m;
  Vec12 g;
  Mat12 h;
  mollifier_derivatives(edges_at_angle(at * (1.0 - 1e-9)), eps_x, m, g, h);
  EXPECT_NEAR(m, 1.0, 1e-12);
  EXPECT_LT(g.norm(), 1e-6);
  mollifier_derivatives(edges_at_angle(at * 1.01), eps_x, m, g, h);
  EXPECT_EQ(m, 1.0);
  EXPECT_EQ(g.norm(), 0.0);
  EXPECT_EQ(h.norm(), 0.0);
}

TEST(EdgeEdgeMollifier, DerivativesMatchFiniteDifferences) {
  const double eps_x = mollifier_threshold(edges_at_angle(0.0));
  for (double fraction : {0.0, 1e-6, 0.1, 0.5, 0.9}) {
    const double theta = std::asin(std::sqrt(fraction * eps_x) / 2.0);
    expect_derivatives_match(edges_at_angle(theta), eps_x, 1e-6, 1e-6);
  }
  // Random nearly parallel edges in general position.
  Random rng(5);
  int mollified = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 a0 = rng.vec(), a1 = rng.vec(), b0 = rng.vec();
    const Vec3 b1 = b0 + rng.uniform(-1.5, 1.5) * (a1 - a0) + 0.02 * rng.vec();
    const Vec12 x = stencil(a0, a1, b0, b1);
    const double eps = mollifier_threshold(x);
    if (mollifier(x, eps) < 1.0) ++mollified;
    expect_derivatives_match(x, eps, 1e-7, 1e-6);
  }
  EXPECT_GT(mollified, 50);
}
