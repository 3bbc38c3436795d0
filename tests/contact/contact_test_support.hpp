#pragma once
/// @file Test helpers for the contact primitives: reference distances computed independently of
/// core/contact (brute-force sampling and a textbook candidate enumeration), random stencils for
/// every closest-pair region, and central finite differences.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "contact/primitive_distance.hpp"

namespace progsim::contact_test {

/// Stacks four vertices into a stencil (12).
inline Vec12 stencil(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Vec12 x;
  x << a, b, c, d;
  return x;
}

/// Vertex k of a stencil.
inline Vec3 vertex(const Vec12& x, int k) {
  return x.segment<3>(3 * k);
}

/// The point of the closed segment [a, b] closest to p (clamped projection).
inline Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 u = b - a;
  const double uu = u.squaredNorm();
  const double t = uu > 0.0 ? std::clamp((p - a).dot(u) / uu, 0.0, 1.0) : 0.0;
  return a + t * u;
}

/// Distance from p to the closed segment [a, b].
inline double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  return (p - closest_on_segment(p, a, b)).norm();
}

/// Brute force: min distance from p to the points of a barycentric grid with n subdivisions per
/// side of the triangle (x1, x2, x3). Exceeds the true distance by at most max edge length / n.
inline double sampled_point_triangle_distance(const Vec12& x, int n) {
  const Vec3 p = vertex(x, 0), t0 = vertex(x, 1), t1 = vertex(x, 2), t2 = vertex(x, 3);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const double b1 = double(i) / n, b2 = double(j) / n;
      best = std::min(best, (p - ((1.0 - b1 - b2) * t0 + b1 * t1 + b2 * t2)).norm());
    }
  }
  return best;
}

/// Brute force: min over n + 1 points of segment a of their exact distance to segment b.
/// Exceeds the true distance by at most ‖ea‖ / (2n).
inline double sampled_edge_edge_distance(const Vec12& x, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    const double s = double(i) / n;
    const Vec3 p = (1.0 - s) * vertex(x, 0) + s * vertex(x, 1);
    best = std::min(best, point_segment_distance(p, vertex(x, 2), vertex(x, 3)));
  }
  return best;
}

/// Textbook reference: the smaller of the distances to the three edges and, if p projects
/// inside, to the projection (2 × 2 normal equations). Every candidate is a true pair of points,
/// so the result never underestimates.
inline double reference_point_triangle_distance(const Vec12& x) {
  const Vec3 p = vertex(x, 0), t0 = vertex(x, 1), t1 = vertex(x, 2), t2 = vertex(x, 3);
  double best = std::min({point_segment_distance(p, t0, t1), point_segment_distance(p, t1, t2),
                          point_segment_distance(p, t2, t0)});
  Eigen::Matrix<double, 3, 2> e;
  e << t1 - t0, t2 - t0;
  const Eigen::Matrix2d gram = e.transpose() * e;
  if (std::abs(gram.determinant()) > 1e-14 * gram.trace() * gram.trace()) {
    const Vec2 b = gram.inverse() * (e.transpose() * (p - t0));
    if (b.minCoeff() >= 0.0 && b.sum() <= 1.0) best = std::min(best, (p - t0 - e * b).norm());
  }
  return best;
}

/// Textbook reference: the smallest of the four endpoint–segment distances and, if the lines'
/// closest points lie inside both segments, their distance (2 × 2 normal equations).
inline double reference_edge_edge_distance(const Vec12& x) {
  const Vec3 a0 = vertex(x, 0), a1 = vertex(x, 1), b0 = vertex(x, 2), b1 = vertex(x, 3);
  double best = std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                          point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
  Eigen::Matrix<double, 3, 2> e;
  e << a1 - a0, b0 - b1;
  const Eigen::Matrix2d gram = e.transpose() * e;
  if (std::abs(gram.determinant()) > 1e-14 * gram.trace() * gram.trace()) {
    const Vec2 st = gram.inverse() * (e.transpose() * (b0 - a0));
    if (st.minCoeff() >= 0.0 && st.maxCoeff() <= 1.0) {
      best = std::min(best, (a0 + st[0] * (a1 - a0) - (b0 + st[1] * (b1 - b0))).norm());
    }
  }
  return best;
}

/// Seeded uniform random numbers and vectors.
class Random {
 public:
  explicit Random(unsigned seed) : engine_(seed) {}
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(engine_); }
  /// Uniform in the cube [−r, r)³.
  Vec3 vec(double r = 1.0) { return Vec3(uniform(-r, r), uniform(-r, r), uniform(-r, r)); }
  /// Uniform on the unit sphere.
  Vec3 direction() {
    Vec3 v;
    do v = vec();
    while (v.squaredNorm() > 1.0 || v.squaredNorm() < 1e-4);
    return v.normalized();
  }
  /// Uniform integer in [0, n).
  int index(int n) { return std::uniform_int_distribution<>(0, n - 1)(engine_); }

 private:
  std::mt19937 engine_;
};

/// A random point–triangle stencil; `kind` cycles through point placements that reach every
/// region: 0 anywhere, 1 above a spot near/outside the triangle (vertex/edge regions),
/// 2 above the interior, 3 within 1e-7 of an edge's line, 4 in the triangle's plane.
inline Vec12 random_point_triangle(Random& rng, int kind) {
  const Vec3 t0 = rng.vec(), t1 = rng.vec(), t2 = rng.vec();
  const Vec3 n = (t1 - t0).cross(t2 - t0).normalized();
  double b1 = rng.uniform(-1.0, 2.0), b2 = rng.uniform(-1.0, 2.0);
  double height = rng.uniform(-1.0, 1.0);
  if (kind == 2) b1 = rng.uniform(0.05, 0.45), b2 = rng.uniform(0.05, 0.45);
  if (kind == 3) b2 = 1e-7 * rng.uniform(-1.0, 1.0), height = 1e-7 * rng.uniform(-1.0, 1.0);
  if (kind == 4) height = 0.0;
  const Vec3 p = kind == 0 ? rng.vec(2.0) : t0 + b1 * (t1 - t0) + b2 * (t2 - t0) + height * n;
  return stencil(p, t0, t1, t2);
}

/// A random edge–edge stencil; `kind`: 0 anywhere, 1 crossing at a random offset (interior
/// closest points likely), 2 exactly parallel, 3 parallel up to 1e-9 rad, 4 collinear,
/// 5 an endpoint within 1e-7 of the other edge's line, 6 nearly intersecting.
inline Vec12 random_edge_edge(Random& rng, int kind) {
  const Vec3 a0 = rng.vec(), a1 = rng.vec();
  if (kind == 0) return stencil(a0, a1, rng.vec(), rng.vec());
  const Vec3 a = a1 - a0;
  if (kind == 1 || kind == 6) {
    const double offset = kind == 1 ? rng.uniform(-0.5, 0.5) : 1e-9 * rng.uniform(-1.0, 1.0);
    const Vec3 mid = a0 + rng.uniform(0.1, 0.9) * a + offset * a.cross(rng.direction());
    const Vec3 half = rng.uniform(0.2, 1.0) * rng.direction();
    return stencil(a0, a1, mid - rng.uniform(0.1, 1.0) * half, mid + half);
  }
  if (kind <= 4) {
    const Vec3 shift = kind == 4 ? rng.uniform(-2.0, 2.0) * a : rng.vec();
    const Vec3 tilt = kind == 3 ? Vec3(1e-9 * a.norm() * rng.direction()) : Vec3::Zero();
    const double scale = rng.uniform(-1.5, 1.5);
    return stencil(a0, a1, a0 + shift, a0 + shift + scale * a + tilt);
  }
  const Vec3 near_line = a0 + rng.uniform(-0.5, 1.5) * a + 1e-7 * rng.direction();
  return stencil(a0, a1, near_line, near_line + rng.vec());
}

/// ∇f by central differences with step h.
inline Vec12 finite_difference_gradient(const std::function<double(const Vec12&)>& f,
                                        const Vec12& x, double h) {
  Vec12 g;
  for (int i = 0; i < 12; ++i) {
    Vec12 xp = x, xm = x;
    xp[i] += h, xm[i] -= h;
    g[i] = (f(xp) - f(xm)) / (2.0 * h);
  }
  return g;
}

/// ∇²f by central differences of the gradient ∇f with step h.
inline Mat12 finite_difference_hessian(const std::function<Vec12(const Vec12&)>& grad,
                                       const Vec12& x, double h) {
  Mat12 hess;
  for (int i = 0; i < 12; ++i) {
    Vec12 xp = x, xm = x;
    xp[i] += h, xm[i] -= h;
    hess.col(i) = (grad(xp) - grad(xm)) / (2.0 * h);
  }
  return hess;
}

/// Max |a − b| / max(max |b|, floor).
template <typename A, typename B>
double relative_error(const A& a, const B& b, double floor) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), floor);
}

}  // namespace progsim::contact_test
