// Additive CCD: head-on impacts with a known time of impact, thousands of random trajectories
// checked by dense sampling with the reference distance, parallel sliding edges, no relative
// motion, and starts within the thickness.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "contact/additive_ccd.hpp"
#include "contact/contact_test_support.hpp"

using namespace progsim;
using namespace progsim::contact_test;

namespace {

constexpr double kS = 0.1;  // C-IPC's rescaling

/// Reference distance of a stencil (point–triangle or edge–edge).
double reference_distance(const Vec12& x, bool triangle) {
  return triangle ? reference_point_triangle_distance(x) : reference_edge_edge_distance(x);
}

double ccd(const Vec12& x, const Vec12& dx, bool triangle, double thickness, double t_max = 1.0,
           double stop_at = std::numeric_limits<double>::infinity()) {
  return triangle
             ? additive_ccd_point_triangle(x, dx, thickness, kS, t_max, kAccdMaxIterations, stop_at)
             : additive_ccd_edge_edge(x, dx, thickness, kS, t_max, kAccdMaxIterations, stop_at);
}

/// Minimum reference distance over `samples` + 1 equidistant times in [0, t].
double min_distance_until(const Vec12& x, const Vec12& dx, bool triangle, double t, int samples) {
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= samples; ++i) {
    d = std::min(d, reference_distance(x + (t * i / samples) * dx, triangle));
  }
  return d;
}

/// Adds to the first primitive's displacement twice the offset from its centroid to the second
/// primitive's, so that the trajectory passes through the other primitive.
void aim_first_primitive(const Vec12& x, bool triangle, Vec12& dx) {
  const int first = triangle ? 1 : 2;
  Vec3 c1 = Vec3::Zero(), c2 = Vec3::Zero();
  for (int k = 0; k < 4; ++k)
    (k < first ? c1 : c2) += vertex(x, k) / (k < first ? first : 4 - first);
  for (int k = 0; k < first; ++k) dx.segment<3>(3 * k) += 2.0 * (c2 - c1);
}

/// The i-th random query: point–triangle for even i, edge–edge for odd, its stencil of shape
/// variant i/2, displacements of up to `speed` per vertex, every other pair of queries aimed
/// through the other primitive.
struct RandomQuery {
  bool triangle;
  Vec12 x, dx;
};
RandomQuery random_query(Random& rng, int i, double speed) {
  RandomQuery q;
  q.triangle = i % 2 == 0;
  q.x = q.triangle ? random_point_triangle(rng, (i / 2) % 5) : random_edge_edge(rng, (i / 2) % 7);
  for (int k = 0; k < 4; ++k) q.dx.segment<3>(3 * k) = rng.vec(speed);
  if (i % 4 < 2) aim_first_primitive(q.x, q.triangle, q.dx);
  return q;
}

}  // namespace

TEST(AdditiveCcd, HeadOnPointTriangle) {
  // p falls from z = 1 onto the unit triangle at relative speed 2; t* = (1 − ξ)/2.
  const Vec12 x = stencil(Vec3(0.25, 0.25, 1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  for (double xi : {0.0, 0.1}) {
    for (bool both_move : {false, true}) {
      const Vec3 down(0, 0, both_move ? -1 : -2), up(0, 0, both_move ? 1 : 0);
      const Vec12 dx = stencil(down, up, up, up);
      const double t_star = (1.0 - xi) / 2.0;
      const double t = additive_ccd_point_triangle(x, dx, xi, kS, 1.0);
      EXPECT_LT(t, t_star);
      EXPECT_GE(t, (1.0 - kS) * t_star * (1.0 - 1e-12));  // exact l_p: one step of (1 − s) t*
      EXPECT_GE(reference_distance(x + t * dx, true), xi + kS * (1.0 - xi) * (1.0 - 1e-9));
    }
  }
}

TEST(AdditiveCcd, HeadOnEdgeEdge) {
  // Crossing edges 1 apart approach at relative speed 2; t* = (1 − ξ)/2.
  const Vec12 x = stencil(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 1), Vec3(0, 1, 1));
  const Vec3 zero = Vec3::Zero(), down(0, 0, -2);
  const Vec12 dx = stencil(zero, zero, down, down);
  const double xi = 0.05, t_star = (1.0 - xi) / 2.0;
  const double t = additive_ccd_edge_edge(x, dx, xi, kS, 1.0);
  EXPECT_LT(t, t_star);
  EXPECT_GE(t, (1.0 - kS) * t_star * (1.0 - 1e-12));
  EXPECT_GE(reference_distance(x + t * dx, false), xi + kS * (1.0 - xi) * (1.0 - 1e-9));
  // A smaller t_max caps the step.
  EXPECT_EQ(additive_ccd_edge_edge(x, dx, xi, kS, 0.2), 0.2);
}

TEST(AdditiveCcd, RandomTrajectoriesNeverGetCloserThanThickness) {
  Random rng(6);
  int collisions = 0, free = 0;
  for (int i = 0; i < 6000; ++i) {
    const auto [triangle, x, dx] = random_query(rng, i, 1.5);
    const double xi = std::array<double, 4>{0.0, 1e-3, 1e-2, 5e-2}[rng.index(4)];
    const double d0 = reference_distance(x, triangle);
    if (d0 < xi + 1e-6) continue;  // starts in (or within rounding of) contact: tested below
    const double t = ccd(x, dx, triangle, xi);
    ASSERT_GE(t, 0.0);
    ASSERT_LE(t, 1.0);
    const double d_min = min_distance_until(x, dx, triangle, t, 200);
    ASSERT_GT(d_min, xi) << "i = " << i << ", t = " << t << "\nx = " << x.transpose()
                         << "\ndx = " << dx.transpose();
    if (t < 1.0) {
      ++collisions;
      // Stopped by the gap criterion: at least s(d₀ − ξ) of the gap is left.
      ASSERT_GE(reference_distance(x + t * dx, triangle) - xi, kS * (d0 - xi) * (1.0 - 1e-6));
    } else {
      ++free;
    }
  }
  EXPECT_GT(collisions, 1000);
  EXPECT_GT(free, 1000);
}

TEST(AdditiveCcd, StoppingAtAKnownBoundGivesExactlyTheMinimumOfBoth) {
  // A caller with a running minimum over pairs passes it as stop_at; the overall minimum must
  // not depend on the order the pairs ran in, so each result is exactly min(t, stop_at).
  Random rng(11);
  int cut = 0, kept = 0;
  for (int i = 0; i < 4000; ++i) {
    const auto [triangle, x, dx] = random_query(rng, i, i % 3 == 0 ? 20.0 : 1.5);
    const double xi = std::array<double, 3>{0.0, 1e-3, 1e-2}[rng.index(3)];
    if (reference_distance(x, triangle) < xi + 1e-6) continue;
    const double t = ccd(x, dx, triangle, xi);
    for (double stop_at : {0.0, 0.25 * t, 0.5, 0.999 * t, t, 0.9, 1.0, 2.0}) {
      ASSERT_EQ(ccd(x, dx, triangle, xi, 1.0, stop_at), std::min(t, stop_at))
          << "i = " << i << ", stop_at = " << stop_at;
      (stop_at < t ? cut : kept) += 1;
    }
  }
  EXPECT_GT(cut, 4000);
  EXPECT_GT(kept, 4000);
}

TEST(AdditiveCcd, ReturnsBeforeTheSampledTimeOfImpact) {
  // The returned t never passes the first sampled time the pair comes within ξ.
  Random rng(7);
  for (int i = 0; i < 1000; ++i) {
    const bool triangle = i % 2 == 0;
    const Vec12 x = triangle ? random_point_triangle(rng, 0) : random_edge_edge(rng, 0);
    Vec12 dx;
    for (int k = 0; k < 4; ++k) dx.segment<3>(3 * k) = rng.vec(2.0);
    const double xi = 0.02;
    if (reference_distance(x, triangle) <= xi) continue;
    const double t = ccd(x, dx, triangle, xi);
    for (int j = 1; j <= 1000; ++j) {
      const double tj = j / 1000.0;
      if (reference_distance(x + tj * dx, triangle) <= xi) {
        ASSERT_LT(t, tj) << "i = " << i;
        break;
      }
    }
  }
}

TEST(AdditiveCcd, ParallelSlidingEdges) {
  // Edge b slides along edge a, 0.1 above it: the distance stays 0.1 > ξ.
  const Vec12 x = stencil(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, 0.1), Vec3(1.5, 0, 0.1));
  const Vec3 zero = Vec3::Zero(), slide(-2, 0, 0);
  const double xi = 0.01;
  EXPECT_EQ(additive_ccd_edge_edge(x, stencil(zero, zero, slide, slide), xi, kS, 1.0), 1.0);
  // Sliding while approaching at speed 0.2: t* = (0.1 − ξ)/0.2, still overlapping then.
  const Vec3 approach(-2, 0, -0.2);
  const Vec12 dx = stencil(zero, zero, approach, approach);
  const double t_star = (0.1 - xi) / 0.2;
  const double t = additive_ccd_edge_edge(x, dx, xi, kS, 1.0);
  EXPECT_LT(t, t_star);
  EXPECT_GT(t, 0.5 * t_star);
  EXPECT_GT(min_distance_until(x, dx, false, t, 1000), xi);
  // The steps of C-IPC Alg. 1 with the analytic gap 0.09 − 0.2t and, after removing the mean
  // displacement (−1, 0, −0.1), l_p = 2‖(1, 0, 0.1)‖.
  const double l_p = 2.0 * std::sqrt(1.01);
  const auto gap = [](double time) { return 0.09 - 0.2 * time; };
  double expected = 0.0, step = (1.0 - kS) * gap(0.0) / l_p;
  while (expected == 0.0 || gap(expected + step) >= kS * gap(0.0)) {
    expected += step;
    step = 0.9 * gap(expected) / l_p;
  }
  EXPECT_NEAR(t, expected, 1e-12);
}

TEST(AdditiveCcd, NoRelativeMotionReturnsTMax) {
  const Vec12 x = stencil(Vec3(0.2, 0.2, 0.5), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_EQ(additive_ccd_point_triangle(x, Vec12::Zero(), 0.01, kS, 1.0), 1.0);
  const Vec3 shift(3, -7, 11);  // a common translation is no relative motion
  EXPECT_EQ(additive_ccd_point_triangle(x, stencil(shift, shift, shift, shift), 0.01, kS, 0.7),
            0.7);
  EXPECT_EQ(additive_ccd_edge_edge(x, stencil(shift, shift, shift, shift), 0.01, kS, 1.0), 1.0);
  // Moving apart never collides.
  const Vec3 up(0, 0, 1), zero = Vec3::Zero();
  EXPECT_EQ(additive_ccd_point_triangle(x, stencil(up, zero, zero, zero), 0.01, kS, 1.0), 1.0);
}

TEST(AdditiveCcd, StartWithinThicknessReturnsZero) {
  const Vec12 x = stencil(Vec3(0.2, 0.2, 0.005), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  const Vec3 up(0, 0, 1), zero = Vec3::Zero();
  const Vec12 dx = stencil(up, zero, zero, zero);
  EXPECT_EQ(additive_ccd_point_triangle(x, dx, 0.01, kS, 1.0), 0.0);
  EXPECT_EQ(additive_ccd_point_triangle(x, dx, 0.005, kS, 1.0), 0.0);  // d = ξ
  EXPECT_EQ(additive_ccd_point_triangle(x, Vec12::Zero(), 0.01, kS, 1.0), 0.0);
  // Touching with zero thickness.
  const Vec12 touching = stencil(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 1, 0));
  EXPECT_EQ(additive_ccd_edge_edge(touching, dx, 0.0, kS, 1.0), 0.0);
}

TEST(AdditiveCcd, GapAtRoundingLevelStopsAtTheIterationCap) {
  // Collinear overlapping edges measure a distance of ~1e-16: the advancement creeps in steps of
  // that size and the iteration cap ends it with a tiny but safe t.
  const Vec12 x =
      stencil(Vec3(0.1, 0.2, 0.3), Vec3(0.7, 0.5, 0.9), Vec3(0.4, 0.35, 0.6), Vec3(1.3, 0.8, 1.5));
  const double d0 = std::sqrt(distance_squared(x, classify_edge_edge(x)));
  ASSERT_GT(d0, 0.0);
  ASSERT_LT(d0, 1e-14);
  Vec12 dx;
  dx << 0, 0, 1, 0, 0, 1, 0, 0, -1, 0, 0, -1;
  const double t = additive_ccd_edge_edge(x, dx, 0.0, kS, 1.0);
  EXPECT_GE(t, 0.0);
  EXPECT_LT(t, 1e-6);
  EXPECT_GT(distance_squared(x + t * dx, classify_edge_edge(x + t * dx)), 0.0);
}

TEST(AdditiveCcd, SlidingAtATinyGapCostsNoMoreThanAnOrdinaryQuery) {
  // Issue 33 §7: a point sliding over a triangle (or an edge over a crossing edge) at a gap far
  // below its motion. The distance never changes, so the whole motion is safe; conservative
  // advancement alone creeps by 0.9 gap / l_p per iteration (10⁶ of them here, ~0.1 s). The
  // distance from the triangle's plane (the other edge's line) bounds it over the whole
  // motion: t = 1 even with the iteration cap at 2, and every sampled time stays above ξ.
  const Vec3 zero = Vec3::Zero();
  for (double gap : {1e-6, 1e-9}) {
    const Vec12 pt = stencil(Vec3(0.2, 0.2, gap), zero, Vec3(1, 0, 0), Vec3(0, 1, 0));
    const Vec12 slide = stencil(Vec3(0.5, 0.3, 0), zero, zero, zero);
    EXPECT_EQ(additive_ccd_point_triangle(pt, slide, 0.0, kS, 1.0, 2), 1.0) << gap;
    EXPECT_GT(min_distance_until(pt, slide, true, 1.0, 1000), 0.9 * gap);
    // The triangle slides and turns about the normal under a still point: the same.
    Vec12 turn = Vec12::Zero();
    for (int k = 1; k < 4; ++k) turn.segment<3>(3 * k) = Vec3(0, 0, 1).cross(vertex(pt, k)) * 0.3;
    EXPECT_EQ(additive_ccd_point_triangle(pt, turn, 0.0, kS, 1.0, 2), 1.0) << gap;
    const Vec12 ee = stencil(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, gap), Vec3(0, 1, gap));
    const Vec3 along(0.4, 0.3, 0);
    EXPECT_EQ(additive_ccd_edge_edge(ee, stencil(zero, zero, along, along), 0.0, kS, 1.0, 2), 1.0)
        << gap;
  }
  // Sinking to half the gap while sliding stays certified (above ξ + s(d₀ − ξ) = 0.1 µm).
  const Vec12 pt = stencil(Vec3(0.2, 0.2, 1e-6), zero, Vec3(1, 0, 0), Vec3(0, 1, 0));
  const Vec12 half = stencil(Vec3(0.01, 0, -0.5e-6), zero, zero, zero);
  EXPECT_EQ(additive_ccd_point_triangle(pt, half, 0.0, kS, 1.0, 2), 1.0);
  EXPECT_GT(min_distance_until(pt, half, true, 1.0, 1000), 0.49e-6);
  // Sinking through the plane is not certified: the advancement stops before the impact at 0.5.
  const Vec12 sink = stencil(Vec3(0.01, 0, -2e-6), zero, zero, zero);
  const double t_sink = additive_ccd_point_triangle(pt, sink, 0.0, kS, 1.0);
  EXPECT_LT(t_sink, 0.5);
  EXPECT_GT(t_sink, 0.4);
  EXPECT_GT(min_distance_until(pt, sink, true, t_sink, 1000), 0.0);
  // A tumbling triangle passes through the point near t = 0.12, and f = (a × b)·c has the same
  // sign at t = 0 and 1 (0.02 and 0.055): only its critical points refuse the certificate,
  // which would otherwise return t = 1 through the impact.
  const Vec12 tumble_start = stencil(Vec3(0.3, 0.3, 0.02), zero, Vec3(1, 0, 0), Vec3(0, 1, 0));
  const Vec12 tumble = stencil(Vec3(0, -0.25, -0.06), Vec3(0.3, 0.45, 0.16),
                               Vec3(-0.41, 0.37, -0.25), Vec3(0.44, -0.54, 0.46));
  const double t_tumble = additive_ccd_point_triangle(tumble_start, tumble, 0.0, kS, 1.0);
  EXPECT_LT(t_tumble, 0.15);
  EXPECT_GT(min_distance_until(tumble_start, tumble, true, t_tumble, 1000), 0.0);
  // A certified query with t_max ≠ 1 returns that t_max.
  EXPECT_EQ(additive_ccd_point_triangle(pt, half, 0.0, kS, 0.37, 2), 0.37);
}

TEST(AdditiveCcd, SlidingParallelEdgesAtATinyGapAreCutShortByTheIterationCap) {
  // Parallel edges span no plane, so the certificate does not apply: each iteration advances by
  // at most 0.9 gap / l_p, and a cap of 1000 ends the step at ~900 gaps of motion, still safe.
  const double gap = 1e-6;
  const Vec12 x = stencil(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, gap), Vec3(1.5, 0, gap));
  const Vec3 zero = Vec3::Zero(), slide(-0.01, 0, 0);
  const Vec12 dx = stencil(zero, zero, slide, slide);
  const double t = additive_ccd_edge_edge(x, dx, 0.0, kS, 1.0, 1000);
  const double l_p = 2.0 * 0.005;  // centred: max ‖da‖ + max ‖db‖
  EXPECT_NEAR(t, 1000 * 0.9 * gap / l_p, 0.02 * t);
  EXPECT_GT(min_distance_until(x, dx, false, t, 1000), 0.0);
}

TEST(AdditiveCcd, ANonFiniteMotionHasNoSafeStep) {
  // Issue 33 §7: NaN used to run the advancement to its cap and return NaN, which std::min in a
  // caller dropped, admitting the whole step. Both queries return NaN at once.
  const Vec12 x = stencil(Vec3(0.2, 0.2, 0.5), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Vec12 dx = Vec12::Zero();
    dx[4] = bad;
    EXPECT_TRUE(std::isnan(additive_ccd_point_triangle(x, dx, 0.0, kS, 1.0)));
    EXPECT_TRUE(std::isnan(additive_ccd_edge_edge(x, dx, 0.0, kS, 1.0)));
    Vec12 y = x;
    y[0] = bad;
    EXPECT_TRUE(std::isnan(additive_ccd_point_triangle(y, Vec12::Zero(), 0.0, kS, 1.0)));
    EXPECT_TRUE(std::isnan(additive_ccd_edge_edge(y, Vec12::Zero(), 0.0, kS, 1.0)));
  }
}
