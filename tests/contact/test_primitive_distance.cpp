// Primitive distances: classification of known configurations, distances against brute-force
// sampling and a textbook reference over every region (incl. parallel and degenerate cases),
// gradient and Hessian against finite differences per distance type, closest-point weights.
#include <gtest/gtest.h>

#include <map>

#include "contact/contact_test_support.hpp"
#include "contact/primitive_distance.hpp"

using namespace progsim;
using namespace progsim::contact_test;

namespace {

const Vec3 kT0(0, 0, 0), kT1(1, 0, 0), kT2(0, 1, 0);  // unit right triangle in z = 0

void expect_pair(const ClosestPair& pair, DistanceType type, std::array<int, 4> vertices) {
  EXPECT_EQ(pair.type, type);
  EXPECT_EQ(pair.vertices, vertices);
}

/// Checks distance_squared_derivatives at x for the pair classified there (kept fixed).
void expect_derivatives_match(const Vec12& x, const ClosestPair& pair, double step,
                              double tolerance) {
  Vec12 g;
  Mat12 h;
  distance_squared_derivatives(x, pair, g, h);
  const auto value = [&](const Vec12& y) { return distance_squared(y, pair); };
  const auto gradient = [&](const Vec12& y) {
    Vec12 gy;
    Mat12 hy;
    distance_squared_derivatives(y, pair, gy, hy);
    return gy;
  };
  EXPECT_TRUE(g.allFinite() && h.allFinite());
  EXPECT_LT(relative_error(g, finite_difference_gradient(value, x, step), 1e-8), tolerance)
      << "gradient, type " << int(pair.type) << "\nx = " << x.transpose();
  Vec12 g_alone;  // the gradient-only path (closest-point weights), against the same FD
  distance_squared_gradient(x, pair, g_alone);
  EXPECT_LT(relative_error(g_alone, finite_difference_gradient(value, x, step), 1e-8), tolerance)
      << "gradient alone, type " << int(pair.type) << "\nx = " << x.transpose();
  EXPECT_LT(relative_error(h, finite_difference_hessian(gradient, x, step), 1e-8), tolerance)
      << "Hessian, type " << int(pair.type) << "\nx = " << x.transpose();
  EXPECT_LT((h - h.transpose()).cwiseAbs().maxCoeff(), 1e-12 * h.cwiseAbs().maxCoeff());
  // Non-participating vertices have zero rows and columns.
  for (int k = 0; k < 4; ++k) {
    if (std::find(pair.vertices.begin(), pair.vertices.end(), k) != pair.vertices.end()) continue;
    EXPECT_EQ(g.segment<3>(3 * k).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(h.middleRows<3>(3 * k).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(h.middleCols<3>(3 * k).cwiseAbs().maxCoeff(), 0.0);
  }
}

/// Max edge length of the triangle of a point–triangle stencil.
double max_triangle_edge(const Vec12& x) {
  return std::max({(vertex(x, 2) - vertex(x, 1)).norm(), (vertex(x, 3) - vertex(x, 2)).norm(),
                   (vertex(x, 1) - vertex(x, 3)).norm()});
}

}  // namespace

TEST(PrimitiveDistance, ClassifiesPointTriangleRegions) {
  const auto at = [](const Vec3& p) { return stencil(p, kT0, kT1, kT2); };
  Vec12 x = at(Vec3(0.2, 0.3, 0.5));
  expect_pair(classify_point_triangle(x), DistanceType::point_triangle, {0, 1, 2, 3});
  EXPECT_NEAR(distance_squared(x, classify_point_triangle(x)), 0.25, 1e-15);
  x = at(Vec3(-1, -1, 0.3));
  expect_pair(classify_point_triangle(x), DistanceType::point_point, {0, 1, -1, -1});
  EXPECT_NEAR(distance_squared(x, classify_point_triangle(x)), 2.09, 1e-15);
  x = at(Vec3(0.5, -1, 0.2));
  expect_pair(classify_point_triangle(x), DistanceType::point_edge, {0, 1, 2, -1});
  EXPECT_NEAR(distance_squared(x, classify_point_triangle(x)), 1.04, 1e-15);
  x = at(Vec3(2, 2, 0));
  expect_pair(classify_point_triangle(x), DistanceType::point_edge, {0, 2, 3, -1});
  EXPECT_NEAR(distance_squared(x, classify_point_triangle(x)), 4.5, 1e-14);
  x = at(Vec3(0, 3, -1));
  expect_pair(classify_point_triangle(x), DistanceType::point_point, {0, 3, -1, -1});
  EXPECT_NEAR(distance_squared(x, classify_point_triangle(x)), 5.0, 1e-14);
  x = at(Vec3(0.25, 0.25, 0));  // in the triangle
  expect_pair(classify_point_triangle(x), DistanceType::point_triangle, {0, 1, 2, 3});
  EXPECT_EQ(distance_squared(x, classify_point_triangle(x)), 0.0);
  // A degenerate (collinear) triangle is measured as its edges, without dividing by ‖n‖ = 0.
  x = stencil(Vec3(0.5, 1, 0), kT0, kT1, Vec3(2, 0, 0));
  EXPECT_NE(classify_point_triangle(x).type, DistanceType::point_triangle);
  EXPECT_NEAR(distance_squared(x, classify_point_triangle(x)), 1.0, 1e-15);
}

TEST(PrimitiveDistance, ClassifiesEdgeEdgeRegions) {
  Vec12 x = stencil(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 1), Vec3(0, 1, 1));
  expect_pair(classify_edge_edge(x), DistanceType::edge_edge, {0, 1, 2, 3});
  EXPECT_NEAR(distance_squared(x, classify_edge_edge(x)), 1.0, 1e-15);
  // Parallel, overlapping: an endpoint against the other edge.
  x = stencil(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0, 1), Vec3(1.5, 0, 1));
  EXPECT_EQ(classify_edge_edge(x).type, DistanceType::point_edge);
  EXPECT_NEAR(distance_squared(x, classify_edge_edge(x)), 1.0, 1e-15);
  // Collinear, disjoint: the facing endpoints.
  x = stencil(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0));
  expect_pair(classify_edge_edge(x), DistanceType::point_point, {1, 2, -1, -1});
  EXPECT_NEAR(distance_squared(x, classify_edge_edge(x)), 1.0, 1e-15);
  // T shape: endpoint eb0 against the interior of edge a.
  x = stencil(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 0.5, 0), Vec3(0, 2, 0));
  expect_pair(classify_edge_edge(x), DistanceType::point_edge, {2, 0, 1, -1});
  EXPECT_NEAR(distance_squared(x, classify_edge_edge(x)), 0.25, 1e-15);
  // Skew lines whose closest points lie outside the segments: an endpoint pair.
  x = stencil(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 1), Vec3(2, 2, 1));
  expect_pair(classify_edge_edge(x), DistanceType::point_point, {1, 2, -1, -1});
  EXPECT_NEAR(distance_squared(x, classify_edge_edge(x)), 3.0, 1e-15);
  // A zero-length edge is a point.
  x = stencil(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, 1, 0));
  EXPECT_EQ(classify_edge_edge(x).type, DistanceType::point_edge);
  EXPECT_NEAR(distance_squared(x, classify_edge_edge(x)), 1.0, 1e-15);
}

TEST(PrimitiveDistance, PointTriangleMatchesReferences) {
  Random rng(1);
  std::map<DistanceType, int> seen;
  for (int i = 0; i < 5000; ++i) {
    const Vec12 x = random_point_triangle(rng, i % 5);
    const ClosestPair pair = classify_point_triangle(x);
    ++seen[pair.type];
    const double d = std::sqrt(distance_squared(x, pair));
    const double reference = reference_point_triangle_distance(x);
    ASSERT_NEAR(d, reference, 1e-9 * (1.0 + reference)) << "x = " << x.transpose();
    if (i % 25 != 0) continue;
    // Brute force: the samples never beat the exact distance and come within the grid spacing.
    const int n = 300;
    const double sampled = sampled_point_triangle_distance(x, n);
    ASSERT_LE(d, sampled + 1e-12) << "x = " << x.transpose();
    ASSERT_GE(d, sampled - max_triangle_edge(x) / n) << "x = " << x.transpose();
  }
  EXPECT_GT(seen[DistanceType::point_point], 100);
  EXPECT_GT(seen[DistanceType::point_edge], 100);
  EXPECT_GT(seen[DistanceType::point_triangle], 100);
}

TEST(PrimitiveDistance, EdgeEdgeMatchesReferences) {
  Random rng(2);
  std::map<DistanceType, int> seen;
  for (int i = 0; i < 7000; ++i) {
    const int kind = i % 7;
    const Vec12 x = random_edge_edge(rng, kind);
    const ClosestPair pair = classify_edge_edge(x);
    ++seen[pair.type];
    if (kind >= 2 && kind <= 4) {
      EXPECT_NE(pair.type, DistanceType::edge_edge) << "parallel";
    }
    const double d = std::sqrt(distance_squared(x, pair));
    ASSERT_TRUE(std::isfinite(d));
    const double reference = reference_edge_edge_distance(x);
    ASSERT_NEAR(d, reference, 1e-8 * (1.0 + reference))
        << "kind " << kind << ", x = " << x.transpose();
    if (i % 5 != 0) continue;
    const int n = 20000;
    const double sampled = sampled_edge_edge_distance(x, n);
    ASSERT_LE(d, sampled + 1e-12) << "x = " << x.transpose();
    ASSERT_GE(d, sampled - (vertex(x, 1) - vertex(x, 0)).norm() / (2.0 * n))
        << "x = " << x.transpose();
  }
  EXPECT_GT(seen[DistanceType::point_point], 100);
  EXPECT_GT(seen[DistanceType::point_edge], 100);
  EXPECT_GT(seen[DistanceType::edge_edge], 100);
}

TEST(PrimitiveDistance, DerivativesMatchFiniteDifferencesPerType) {
  Random rng(3);
  std::map<DistanceType, int> checked;
  for (int i = 0; i < 400; ++i) {
    const bool triangle = i % 2 == 0;
    const Vec12 x =
        triangle ? random_point_triangle(rng, (i / 2) % 3) : random_edge_edge(rng, (i / 2) % 2);
    const ClosestPair pair = triangle ? classify_point_triangle(x) : classify_edge_edge(x);
    ++checked[pair.type];
    expect_derivatives_match(x, pair, 1e-5, 1e-6);
  }
  EXPECT_GT(checked[DistanceType::point_point], 20);
  EXPECT_GT(checked[DistanceType::point_edge], 20);
  EXPECT_GT(checked[DistanceType::point_triangle], 20);
  EXPECT_GT(checked[DistanceType::edge_edge], 20);
}

TEST(PrimitiveDistance, DerivativesMatchFiniteDifferencesNearDegenerate) {
  // Point 1e-6 from an edge's line (point–edge).
  Vec12 x = stencil(Vec3(0.3, -1e-6, 2e-7), kT0, kT1, kT2);
  ClosestPair pair = classify_point_triangle(x);
  ASSERT_EQ(pair.type, DistanceType::point_edge);
  expect_derivatives_match(x, pair, 1e-8, 1e-6);
  // Point 1e-7 above the triangle (point–triangle).
  x = stencil(Vec3(0.3, 0.3, 1e-7), kT0, kT1, kT2);
  pair = classify_point_triangle(x);
  ASSERT_EQ(pair.type, DistanceType::point_triangle);
  expect_derivatives_match(x, pair, 1e-8, 1e-6);
  // Point 1e-7 from a vertex (point–point).
  x = stencil(Vec3(1 + 1e-7, -1e-7, 0), kT0, kT1, kT2);
  pair = classify_point_triangle(x);
  ASSERT_EQ(pair.type, DistanceType::point_point);
  expect_derivatives_match(x, pair, 1e-9, 1e-6);
  // Edges 1e-3 rad from parallel, closest points in their interiors (edge–edge), and crossing
  // 1e-7 apart.
  for (double angle : {1e-3, 1e-2}) {
    x = stencil(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(-1, -angle, 0.1), Vec3(1, angle, 0.1));
    pair = classify_edge_edge(x);
    ASSERT_EQ(pair.type, DistanceType::edge_edge);
    expect_derivatives_match(x, pair, 1e-4 * angle * angle, 1e-6);
  }
  x = stencil(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 1e-7), Vec3(0.1, 1, 1e-7));
  pair = classify_edge_edge(x);
  ASSERT_EQ(pair.type, DistanceType::edge_edge);
  expect_derivatives_match(x, pair, 1e-8, 1e-6);
  // Exactly parallel edges: an endpoint against the other edge's line.
  x = stencil(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.1, 0.2), Vec3(1.5, 0.1, 0.2));
  pair = classify_edge_edge(x);
  ASSERT_EQ(pair.type, DistanceType::point_edge);
  expect_derivatives_match(x, pair, 1e-6, 1e-6);
}

TEST(PrimitiveDistance, DerivativesKnownValues) {
  // Point 2 above the unit triangle: d² = z², ∇ = (0, 0, 2z) on p and −(β-weighted) on t_k.
  const Vec12 x = stencil(Vec3(0.25, 0.25, 2), kT0, kT1, kT2);
  Vec12 g;
  Mat12 h;
  distance_squared_derivatives(x, classify_point_triangle(x), g, h);
  Vec12 expected;
  expected << 0, 0, 4, 0, 0, -2, 0, 0, -1, 0, 0, -1;
  EXPECT_LT((g - expected).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(h(2, 2), 2.0, 1e-14);
}

TEST(PrimitiveDistance, ClosestPointWeightsSpanTheDistance) {
  Random rng(4);
  for (int i = 0; i < 4000; ++i) {
    const bool triangle = i % 2 == 0;
    const Vec12 x =
        triangle ? random_point_triangle(rng, (i / 2) % 5) : random_edge_edge(rng, (i / 2) % 7);
    const ClosestPair pair = triangle ? classify_point_triangle(x) : classify_edge_edge(x);
    const Eigen::Vector4d w = closest_point_weights(x, pair);
    Vec3 r = Vec3::Zero();
    for (int k = 0; k < 4; ++k) r += w[k] * vertex(x, k);
    const double d = std::sqrt(distance_squared(x, pair));
    ASSERT_NEAR(r.norm(), d, 1e-9 * (1.0 + d)) << "x = " << x.transpose();
    ASSERT_NEAR(w.sum(), 0.0, 1e-12);
    // r points from the second primitive (weights in [−1, 0]) to the first (weights in [0, 1]).
    const int first = triangle ? 1 : 2;
    ASSERT_NEAR(w.head(first).sum(), 1.0, 1e-12);
    ASSERT_GE(w.head(first).minCoeff(), -1e-12);
    ASSERT_LE(w.tail(4 - first).maxCoeff(), 1e-12);
  }
}

TEST(PrimitiveDistance, ClosestPointWeightsKnownValues) {
  Vec12 x = stencil(Vec3(0.25, 0.5, 2), kT0, kT1, kT2);
  EXPECT_LT((closest_point_weights(x, classify_point_triangle(x)) -
             Eigen::Vector4d(1, -0.25, -0.25, -0.5))
                .cwiseAbs()
                .maxCoeff(),
            1e-15);
  x = stencil(Vec3(-1, 0, 0), Vec3(3, 0, 0), Vec3(0, -1, 1), Vec3(0, 3, 1));
  EXPECT_LT(
      (closest_point_weights(x, classify_edge_edge(x)) - Eigen::Vector4d(0.75, 0.25, -0.75, -0.25))
          .cwiseAbs()
          .maxCoeff(),
      1e-15);
  // eb0 against the interior of edge a: r still points from edge b to edge a.
  x = stencil(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 2, 0));
  EXPECT_LT((closest_point_weights(x, classify_edge_edge(x)) - Eigen::Vector4d(0.25, 0.75, -1, 0))
                .cwiseAbs()
                .maxCoeff(),
            1e-15);
}
