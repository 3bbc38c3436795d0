#include "contact/additive_ccd.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace progsim {
namespace {

/// Classifies the closest pair of a stencil (classify_point_triangle or classify_edge_edge).
using Classifier = ClosestPair (*)(const Vec12&);

/// The stencil displacements minus their mean (C-IPC Alg. 1: a common translation does not
/// change the distance, removing it tightens the bound l_p).
Vec12 centered(const Vec12& dx) {
  const Vec3 mean =
      0.25 * (dx.segment<3>(0) + dx.segment<3>(3) + dx.segment<3>(6) + dx.segment<3>(9));
  Vec12 c = dx;
  for (int k = 0; k < 4; ++k) c.segment<3>(3 * k) -= mean;
  return c;
}

/// max ‖d_k‖ over the stencil vertices k ∈ [begin, end).
double max_norm(const Vec12& d, int begin, int end) {
  double m = 0.0;
  for (int k = begin; k < end; ++k) m = std::max(m, d.segment<3>(3 * k).norm());
  return m;
}

/// The gap d − ξ, computed as (d² − ξ²)/(d + ξ) (C-IPC Alg. 1); 0 within the thickness.
double gap(const Vec12& x, Classifier classify, double thickness) {
  const double d_sq = distance_squared(x, classify(x));
  const double xi_sq = thickness * thickness;
  return d_sq <= xi_sq ? 0.0 : (d_sq - xi_sq) / (std::sqrt(d_sq) + thickness);
}

/// Vertex k of a 12-vector stencil.
Vec3 at(const Vec12& v, int k) {
  return v.segment<3>(3 * k);
}

/// The stencil's spanning vectors a, b (of the plane or the two lines) and c (from the first to
/// the other primitive), each at t = 0 and its rate: point–triangle (p, t0, t1, t2) gives
/// a = t1 − t0, b = t2 − t0, c = p − t0; edge–edge (ea0, ea1, eb0, eb1) gives a = ea1 − ea0,
/// b = eb1 − eb0, c = eb0 − ea0.
struct SpanningVectors {
  Vec3 a0, a1, b0, b1, c0, c1;
};

SpanningVectors spanning_vectors(const Vec12& x, const Vec12& dx, bool point_triangle) {
  if (point_triangle)
    return {at(x, 2) - at(x, 1),   at(dx, 2) - at(dx, 1), at(x, 3) - at(x, 1),
            at(dx, 3) - at(dx, 1), at(x, 0) - at(x, 1),   at(dx, 0) - at(dx, 1)};
  return {at(x, 1) - at(x, 0),   at(dx, 1) - at(dx, 0), at(x, 3) - at(x, 2),
          at(dx, 3) - at(dx, 2), at(x, 2) - at(x, 0),   at(dx, 2) - at(dx, 0)};
}

/// A lower bound on the stencil's distance over the whole motion t ∈ [0, t_max], or 0 when
/// none is found. The distance is at least that of the point from the triangle's plane (of the
/// two edges' lines), |f(t)| / ‖n(t)‖ with n = a × b (quadratic in t) and f = n · c, a cubic:
/// when f keeps its sign on [0, t_max], its smallest |f| (at an end or a root of f') over the
/// largest ‖n‖ (bounded by the triangle inequality) bounds the distance from below, with the
/// rounding of f allowed for. This certifies in one evaluation the sliding motions on which
/// conservative advancement needs ~l_p/gap iterations (issue 33 §7).
double plane_distance_bound(const SpanningVectors& v, double t_max) {
  const Vec3 n0 = v.a0.cross(v.b0), n1 = v.a0.cross(v.b1) + v.a1.cross(v.b0), n2 = v.a1.cross(v.b1);
  const double f[4] = {n0.dot(v.c0), n0.dot(v.c1) + n1.dot(v.c0), n1.dot(v.c1) + n2.dot(v.c0),
                       n2.dot(v.c1)};
  const auto cubic = [&](double t) { return ((f[3] * t + f[2]) * t + f[1]) * t + f[0]; };
  double times[4] = {0.0, t_max, -1.0, -1.0};
  const double qa = 3.0 * f[3], qb = 2.0 * f[2], qc = f[1];  // f'(t) = qa t² + qb t + qc
  if (qa != 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      times[2] = q / qa;
      if (q != 0.0) times[3] = qc / q;
    }
  } else if (qb != 0.0) {
    times[2] = -qc / qb;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double t : times) {
    if (!(t >= 0.0 && t <= t_max)) continue;
    const double value = cubic(t);
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  const double smallest = lo > 0.0 ? lo : (hi < 0.0 ? -hi : 0.0);  // 0: f may vanish
  const double a = v.a0.norm() + t_max * v.a1.norm(), b = v.b0.norm() + t_max * v.b1.norm(),
               c = v.c0.norm() + t_max * v.c1.norm();
  const double rounding = 1e-12 * a * b * c;
  const double largest_normal = n0.norm() + t_max * n1.norm() + t_max * t_max * n2.norm();
  return smallest > rounding ? (smallest - rounding) / largest_normal : 0.0;
}

/// Conservative advancement (C-IPC Alg. 1) with centred displacements dx and the bound l_p on
/// the rate at which the distance can shrink. A motion that would take more than
/// kCertifiedAdvances steps is first tried against plane_distance_bound().
/// `raw` is dx before centring (plane_distance_bound() takes differences, which need none).
/// Past t_stop ≤ t_max the advancement returns t_stop (the caller needs no larger t).
double advance(const Vec12& x, const Vec12& dx, const Vec12& raw, double l_p, Classifier classify,
               bool point_triangle, double thickness, double s, double t_max, double t_stop,
               int max_iterations) {
  constexpr double kCertifiedAdvances = 16.0;
  const double g0 = gap(x, classify, thickness);
  if (!std::isfinite(g0) || !std::isfinite(l_p))  // finite input that overflows
    return std::numeric_limits<double>::quiet_NaN();
  if (g0 <= 0.0) return 0.0;
  if (l_p == 0.0) return t_max;
  if (l_p * t_max > kCertifiedAdvances * g0 &&
      plane_distance_bound(spanning_vectors(x, raw, point_triangle), t_max) >= thickness + s * g0)
    return t_max;                     // the distance stays above ξ + s(d₀ − ξ) throughout
  const double g_min = s * g0;        // stop once the gap drops below s(d₀ − ξ)
  double t_l = (1.0 - s) * g0 / l_p;  // first step keeps a gap ≥ s(d₀ − ξ)
  Vec12 xt = x;
  double t = 0.0;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    xt += t_l * dx;
    const double g = gap(xt, classify, thickness);
    if ((t > 0.0 && g < g_min) || g <= 0.0) return t;  // g ≤ 0 only by rounding
    t += t_l;
    if (t > t_stop) return t_stop;
    t_l = 0.9 * g / l_p;  // later steps keep ≥ 10% of the current gap
  }
  return t;
}

}  // namespace

double additive_ccd_point_triangle(const Vec12& x, const Vec12& dx, double thickness, double s,
                                   double t_max, int max_iterations, double stop_at) {
  if (!x.allFinite() || !dx.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  const Vec12 d = centered(dx);
  // l_p = ‖dp‖ + max_k ‖dt_k‖ bounds how fast the distance can shrink (C-IPC Alg. 1)
  const double l_p = d.segment<3>(0).norm() + max_norm(d, 1, 4);
  const double t_stop = std::min(t_max, stop_at);
  return std::min(advance(x, d, dx, l_p, classify_point_triangle, true, thickness, s, t_max, t_stop,
                          max_iterations),
                  stop_at);
}

double additive_ccd_edge_edge(const Vec12& x, const Vec12& dx, double thickness, double s,
                              double t_max, int max_iterations, double stop_at) {
  if (!x.allFinite() || !dx.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  const Vec12 d = centered(dx);
  // l_p = max(‖da0‖, ‖da1‖) + max(‖db0‖, ‖db1‖) (C-IPC Alg. 1)
  const double l_p = max_norm(d, 0, 2) + max_norm(d, 2, 4);
  const double t_stop = std::min(t_max, stop_at);
  return std::min(advance(x, d, dx, l_p, classify_edge_edge, false, thickness, s, t_max, t_stop,
                          max_iterations),
                  stop_at);
}

}  // namespace progsim
