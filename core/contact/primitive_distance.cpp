#include "contact/primitive_distance.hpp"

#include <Eigen/Geometry>
#include <initializer_list>

namespace progsim {
namespace {

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;

/// Two directions whose sin² of the angle between them is below this count as parallel (edges)
/// or degenerate (triangle sides): the line–line and point–plane formulas would divide by ~0.
constexpr double kParallelSinSquared = 1e-16;

/// Position of stencil vertex k.
Vec3 vertex(const Vec12& x, int k) {
  return x.segment<3>(3 * k);
}

/// Number of stencil vertices a pair of this type uses.
int vertex_count(DistanceType type) {
  if (type == DistanceType::point_point) return 2;
  return type == DistanceType::point_edge ? 3 : 4;
}

/// A value with its gradient and Hessian w.r.t. N variables.
template <int N>
struct Jet {
  double value;
  Eigen::Matrix<double, N, 1> grad;
  Eigen::Matrix<double, N, N> hess;
};

/// f = n/d by the quotient rule: ∇f = (∇n − f∇d)/d, ∇²f = (∇²n − f∇²d − ∇d∇fᵀ − ∇f∇dᵀ)/d.
template <int N>
Jet<N> quotient(const Jet<N>& num, const Jet<N>& den) {
  Jet<N> f;
  f.value = num.value / den.value;
  f.grad = (num.grad - f.value * den.grad) / den.value;
  f.hess = (num.hess - f.value * den.hess - den.grad * f.grad.transpose() -
            f.grad * den.grad.transpose()) /
           den.value;
  return f;
}

/// The jet f (N ≤ 9 variables) as a function of 9 variables, zero in the trailing ones.
template <int N>
Jet<9> padded(const Jet<N>& f) {
  Jet<9> g{f.value, Vec9::Zero(), Mat9::Zero()};
  g.grad.template head<N>() = f.grad;
  g.hess.template topLeftCorner<N, N>() = f.hess;
  return g;
}

/// [v]×, the matrix of v × · .
Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// A difference x_plus − x_minus of two stencil vertices.
struct Difference {
  int plus, minus;
};

/// The difference vectors a pair's distance depends on (the first `count` entries):
/// point_point (p − q); point_edge (p − e0, e1 − e0); point_triangle (p − t0, t1 − t0,
/// t2 − t0); edge_edge (ea0 − eb0, ea1 − ea0, eb1 − eb0).
struct Differences {
  std::array<Difference, 3> d;
  int count;
};

/// The differences for the pair's type and vertices.
Differences differences_of(const ClosestPair& pair) {
  const std::array<int, 4>& v = pair.vertices;
  if (pair.type == DistanceType::edge_edge) {
    return {{{{v[0], v[2]}, {v[1], v[0]}, {v[3], v[2]}}}, 3};
  }
  return {{{{v[0], v[1]}, {v[2], v[1]}, {v[3], v[1]}}}, vertex_count(pair.type) - 1};
}

/// The difference vectors at positions x as columns (zero beyond diffs.count).
Mat3 differences(const Vec12& x, const Differences& diffs) {
  Mat3 r = Mat3::Zero();
  for (int k = 0; k < diffs.count; ++k) {
    r.col(k) = vertex(x, diffs.d[k].plus) - vertex(x, diffs.d[k].minus);
  }
  return r;
}

/// ‖v‖² (point–point) w.r.t. r = (v, ·, ·).
Jet<9> point_point_jet(const Mat3& r) {
  Jet<3> f{r.col(0).squaredNorm(), 2.0 * r.col(0), 2.0 * Mat3::Identity()};
  return padded(f);
}

/// ‖v × u‖²/‖u‖² (point to line, v = p − e0, u = e1 − e0) w.r.t. r = (v, u, ·).
Jet<9> point_line_jet(const Mat3& r) {
  Jet<6> num, den{r.col(1).squaredNorm(), Vec6::Zero(), Mat6::Zero()};
  num.value = cross_squared_norm_derivatives(r.col(0), r.col(1), num.grad, num.hess);
  den.grad.tail<3>() = 2.0 * r.col(1);
  den.hess.bottomRightCorner<3, 3>() = 2.0 * Mat3::Identity();
  return padded(quotient(num, den));
}

/// (v·(a × b))²/‖a × b‖² w.r.t. r = (v, a, b): point to plane (v = p − t0, a = t1 − t0,
/// b = t2 − t0) and line to line (v = ea0 − eb0, a = ea1 − ea0, b = eb1 − eb0).
Jet<9> point_plane_jet(const Mat3& r) {
  const Vec3 v = r.col(0), a = r.col(1), b = r.col(2);
  // Triple product s = v·(a × b): ∇s = (a × b, b × v, v × a), ∇²s bilinear off-diagonal blocks.
  Jet<9> s{v.dot(a.cross(b)), Vec9::Zero(), Mat9::Zero()};
  s.grad << a.cross(b), b.cross(v), v.cross(a);
  s.hess.block<3, 3>(0, 3) = -cross_matrix(b);
  s.hess.block<3, 3>(0, 6) = cross_matrix(a);
  s.hess.block<3, 3>(3, 6) = -cross_matrix(v);
  s.hess.block<3, 3>(3, 0) = s.hess.block<3, 3>(0, 3).transpose();
  s.hess.block<3, 3>(6, 0) = s.hess.block<3, 3>(0, 6).transpose();
  s.hess.block<3, 3>(6, 3) = s.hess.block<3, 3>(3, 6).transpose();
  // s²: ∇(s²) = 2s∇s, ∇²(s²) = 2∇s∇sᵀ + 2s∇²s.
  const Jet<9> num{s.value * s.value, 2.0 * s.value * s.grad,
                   2.0 * s.grad * s.grad.transpose() + 2.0 * s.value * s.hess};
  Jet<9> den{0.0, Vec9::Zero(), Mat9::Zero()};
  Vec6 g;
  Mat6 h;
  den.value = cross_squared_norm_derivatives(a, b, g, h);
  den.grad.tail<6>() = g;
  den.hess.bottomRightCorner<6, 6>() = h;
  return quotient(num, den);
}

/// Squared distance of a pair of this type with its derivatives w.r.t. its difference vectors.
Jet<9> difference_jet(const Mat3& r, DistanceType type) {
  if (type == DistanceType::point_point) return point_point_jet(r);
  if (type == DistanceType::point_edge) return point_line_jet(r);
  return point_plane_jet(r);
}

/// Closest pair between stencil vertex p and the closed segment (e0, e1).
ClosestPair classify_point_segment(const Vec12& x, int p, int e0, int e1) {
  const Vec3 u = vertex(x, e1) - vertex(x, e0);
  const double t = (vertex(x, p) - vertex(x, e0)).dot(u);  // projection parameter × ‖u‖²
  if (t <= 0.0) return {DistanceType::point_point, {p, e0, -1, -1}};
  if (t >= u.squaredNorm()) return {DistanceType::point_point, {p, e1, -1, -1}};
  return {DistanceType::point_edge, {p, e0, e1, -1}};
}

/// The candidate pair with the smallest distance.
ClosestPair nearest(const Vec12& x, std::initializer_list<ClosestPair> candidates) {
  const ClosestPair* best = candidates.begin();
  double best_distance = distance_squared(x, *best);
  for (const ClosestPair& c : candidates) {
    const double d = distance_squared(x, c);
    if (d < best_distance) best = &c, best_distance = d;
  }
  return *best;
}

/// Whether ‖a × b‖² (given as n_sq) is large enough relative to ‖a‖²‖b‖² for a and b to span
/// a plane reliably.
bool spans_plane(double n_sq, const Vec3& a, const Vec3& b) {
  return n_sq > kParallelSinSquared * a.squaredNorm() * b.squaredNorm();
}

}  // namespace

ClosestPair classify_point_triangle(const Vec12& x) {
  const Vec3 t0 = vertex(x, 1);
  const Vec3 v = vertex(x, 0) - t0, a = vertex(x, 2) - t0, b = vertex(x, 3) - t0;
  const Vec3 n = a.cross(b);
  const double n_sq = n.squaredNorm();
  if (spans_plane(n_sq, a, b)) {
    // Barycentric coordinates (β1, β2) of p's projection, times ‖n‖² (Lagrange's identity).
    const double b1 = v.cross(b).dot(n), b2 = a.cross(v).dot(n);
    if (b1 > 0.0 && b2 > 0.0 && b1 + b2 < n_sq) {
      return {DistanceType::point_triangle, {0, 1, 2, 3}};
    }
  }
  // The projection lies outside the triangle: the closest point is on its boundary.
  return nearest(x, {classify_point_segment(x, 0, 1, 2), classify_point_segment(x, 0, 2, 3),
                     classify_point_segment(x, 0, 3, 1)});
}

ClosestPair classify_edge_edge(const Vec12& x) {
  const Vec3 w = vertex(x, 0) - vertex(x, 2);
  const Vec3 a = vertex(x, 1) - vertex(x, 0), b = vertex(x, 3) - vertex(x, 2);
  const Vec3 n = a.cross(b);
  const double n_sq = n.squaredNorm();
  if (spans_plane(n_sq, a, b)) {
    // Closest-point parameters of the two lines, times ‖n‖² (normal equations, Lagrange's
    // identity): α = ((b × w)·n)/‖n‖², β = ((a × w)·n)/‖n‖².
    const double alpha = b.cross(w).dot(n), beta = a.cross(w).dot(n);
    if (alpha > 0.0 && alpha < n_sq && beta > 0.0 && beta < n_sq) {
      return {DistanceType::edge_edge, {0, 1, 2, 3}};
    }
  }
  // Otherwise a parameter is clamped: the closest points include an endpoint.
  return nearest(x, {classify_point_segment(x, 0, 2, 3), classify_point_segment(x, 1, 2, 3),
                     classify_point_segment(x, 2, 0, 1), classify_point_segment(x, 3, 0, 1)});
}

double distance_squared(const Vec12& x, const ClosestPair& pair) {
  const Mat3 r = differences(x, differences_of(pair));
  // ‖p − q‖² (IPC §4, point–point)
  if (pair.type == DistanceType::point_point) return r.col(0).squaredNorm();
  // ‖(p − e0) × (e1 − e0)‖²/‖e1 − e0‖² (IPC §4, point–edge)
  if (pair.type == DistanceType::point_edge) {
    return r.col(0).cross(r.col(1)).squaredNorm() / r.col(1).squaredNorm();
  }
  // IPC §4: point–triangle ((p − t0)·n)²/‖n‖², n = (t1 − t0) × (t2 − t0); edge–edge
  // ((ea0 − eb0)·n)²/‖n‖², n = ea × eb
  const Vec3 n = r.col(1).cross(r.col(2));
  const double s = r.col(0).dot(n);
  return s * s / n.squaredNorm();
}

void distance_squared_derivatives(const Vec12& x, const ClosestPair& pair, Vec12& grad,
                                  Mat12& hess) {
  const Differences diffs = differences_of(pair);
  const Jet<9> f = difference_jet(differences(x, diffs), pair.type);
  // Chain rule through r_k = x_plus − x_minus: ±1 per vertex block.
  grad.setZero();
  hess.setZero();
  for (int k = 0; k < diffs.count; ++k) {
    const Difference dk = diffs.d[k];
    grad.segment<3>(3 * dk.plus) += f.grad.segment<3>(3 * k);
    grad.segment<3>(3 * dk.minus) -= f.grad.segment<3>(3 * k);
    for (int l = 0; l < diffs.count; ++l) {
      const Difference dl = diffs.d[l];
      const Mat3 block = f.hess.block<3, 3>(3 * k, 3 * l);
      hess.block<3, 3>(3 * dk.plus, 3 * dl.plus) += block;
      hess.block<3, 3>(3 * dk.plus, 3 * dl.minus) -= block;
      hess.block<3, 3>(3 * dk.minus, 3 * dl.plus) -= block;
      hess.block<3, 3>(3 * dk.minus, 3 * dl.minus) += block;
    }
  }
}

void distance_squared_gradient(const Vec12& x, const ClosestPair& pair, Vec12& grad) {
  const Eigen::Vector4d w = closest_point_weights(x, pair);
  Vec3 r = Vec3::Zero();  // r = Σ_k w_k x_k, from the second primitive's closest point
  for (int k = 0; k < 4; ++k) r += w[k] * vertex(x, k);
  for (int k = 0; k < 4; ++k) grad.segment<3>(3 * k) = 2.0 * w[k] * r;  // envelope theorem
}

Eigen::Vector4d closest_point_weights(const Vec12& x, const ClosestPair& pair) {
  const std::array<int, 4>& v = pair.vertices;
  const Mat3 r = differences(x, differences_of(pair));
  Eigen::Vector4d w = Eigen::Vector4d::Zero();
  w[v[0]] = 1.0;
  if (pair.type == DistanceType::point_point) {
    w[v[1]] = -1.0;
  } else if (pair.type == DistanceType::point_edge) {
    // Closest point e0 + t(e1 − e0), t = (p − e0)·(e1 − e0)/‖e1 − e0‖².
    const double t = r.col(0).dot(r.col(1)) / r.col(1).squaredNorm();
    w[v[1]] = t - 1.0, w[v[2]] = -t;
  } else {
    const Vec3 n = r.col(1).cross(r.col(2));
    const double n_sq = n.squaredNorm();
    if (pair.type == DistanceType::point_triangle) {
      // Barycentric coordinates of p's projection: β1 = ((v × b)·n)/‖n‖², β2 = ((a × v)·n)/‖n‖².
      const double b1 = r.col(0).cross(r.col(2)).dot(n) / n_sq;
      const double b2 = r.col(1).cross(r.col(0)).dot(n) / n_sq;
      w[v[1]] = b1 + b2 - 1.0, w[v[2]] = -b1, w[v[3]] = -b2;
    } else {
      // Line parameters α = ((b × w)·n)/‖n‖², β = ((a × w)·n)/‖n‖², w = ea0 − eb0.
      const double alpha = r.col(2).cross(r.col(0)).dot(n) / n_sq;
      const double beta = r.col(1).cross(r.col(0)).dot(n) / n_sq;
      w[v[0]] = 1.0 - alpha, w[v[1]] = alpha, w[v[2]] = beta - 1.0, w[v[3]] = -beta;
    }
  }
  // A point of edge b (stencil vertex 2 or 3) measured against edge a: flip to point b → a.
  return v[0] < 2 ? w : Eigen::Vector4d(-w);
}

Vec6 cross_squared_norm_gradient(const Vec3& a, const Vec3& b) {
  // ‖a × b‖² = ‖a‖²‖b‖² − (a·b)²: ∇_a = 2 b × (a × b), ∇_b = 2 (a × b) × a.
  const Vec3 c = a.cross(b);
  Vec6 grad;
  grad << 2.0 * b.cross(c), 2.0 * c.cross(a);
  return grad;
}

double cross_squared_norm_derivatives(const Vec3& a, const Vec3& b, Vec6& grad, Mat6& hess) {
  grad = cross_squared_norm_gradient(a, b);
  const Mat3 id = Mat3::Identity();
  hess.topLeftCorner<3, 3>() = 2.0 * (b.squaredNorm() * id - b * b.transpose());
  hess.bottomRightCorner<3, 3>() = 2.0 * (a.squaredNorm() * id - a * a.transpose());
  hess.topRightCorner<3, 3>() =
      4.0 * a * b.transpose() - 2.0 * b * a.transpose() - 2.0 * a.dot(b) * id;
  hess.bottomLeftCorner<3, 3>() = hess.topRightCorner<3, 3>().transpose();
  return a.cross(b).squaredNorm();
}

}  // namespace progsim
