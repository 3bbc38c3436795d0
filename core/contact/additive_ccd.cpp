#include "contact/additive_ccd.hpp"

#include <algorithm>
#include <cmath>

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

/// Conservative advancement (C-IPC Alg. 1) with centred displacements dx and the bound l_p on
/// the rate at which the distance can shrink.
double advance(const Vec12& x, const Vec12& dx, double l_p, Classifier classify, double thickness,
               double s, double t_max, int max_iterations) {
  const double g0 = gap(x, classify, thickness);
  if (g0 <= 0.0) return 0.0;
  if (l_p == 0.0) return t_max;
  const double g_min = s * g0;        // stop once the gap drops below s(d₀ − ξ)
  double t_l = (1.0 - s) * g0 / l_p;  // first step keeps a gap ≥ s(d₀ − ξ)
  Vec12 xt = x;
  double t = 0.0;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    xt += t_l * dx;
    const double g = gap(xt, classify, thickness);
    if ((t > 0.0 && g < g_min) || g <= 0.0) return t;  // g ≤ 0 only by rounding
    t += t_l;
    if (t > t_max) return t_max;
    t_l = 0.9 * g / l_p;  // later steps keep ≥ 10% of the current gap
  }
  return t;
}

}  // namespace

double additive_ccd_point_triangle(const Vec12& x, const Vec12& dx, double thickness, double s,
                                   double t_max, int max_iterations) {
  const Vec12 d = centered(dx);
  // l_p = ‖dp‖ + max_k ‖dt_k‖ bounds how fast the distance can shrink (C-IPC Alg. 1)
  const double l_p = d.segment<3>(0).norm() + max_norm(d, 1, 4);
  return advance(x, d, l_p, classify_point_triangle, thickness, s, t_max, max_iterations);
}

double additive_ccd_edge_edge(const Vec12& x, const Vec12& dx, double thickness, double s,
                              double t_max, int max_iterations) {
  const Vec12 d = centered(dx);
  // l_p = max(‖da0‖, ‖da1‖) + max(‖db0‖, ‖db1‖) (C-IPC Alg. 1)
  const double l_p = max_norm(d, 0, 2) + max_norm(d, 2, 4);
  return advance(x, d, l_p, classify_edge_edge, thickness, s, t_max, max_iterations);
}

}  // namespace progsim
