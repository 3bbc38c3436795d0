#pragma once
/// @file Additive continuous collision detection (ACCD; C-IPC, Li, Kaufman & Jiang 2021,
/// Alg. 1): a conservative time of impact for linear trajectories of a point–triangle or
/// edge–edge stencil that keeps the pair at least a thickness ξ apart.
#include <limits>

#include "contact/primitive_distance.hpp"

namespace progsim {

/// Default iteration cap of the advancement; reaching it returns the (safe) t reached so far.
inline constexpr int kAccdMaxIterations = 1000000;

/// Largest safe step t ∈ [0, t_max] along x(t) = x + t·dx for a point–triangle stencil
/// (p, t0, t1, t2) that conservative advancement finds: the distance stays above ξ on [0, t]
/// and, if t < t_max, is at least ξ + s·(d(x) − ξ) at t. Returns 0 if the pair already is within
/// the thickness (d(x) ≤ ξ), t_max if there is no relative motion or the advancement reaches
/// t_max before the gap falls below s·(d(x) − ξ).
/// Each iteration advances t by at most 0.9 (d(x(t)) − ξ)/l_p (l_p bounds how fast the distance
/// can shrink), so a pair sliding along at a gap small against its motion needs about
/// l_p/gap iterations; at the cap `max_iterations` it returns the t reached, safe but short
/// (about 0.9 · max_iterations · gap / l_p). A gap at rounding level may end so with a tiny t.
/// Before such a long advancement, the distance of the point from the triangle's plane (of the
/// two edges' lines) over the whole motion, a cubic over a quadratic, is bounded from below: a
/// pair sliding at a small gap that stays at least ξ + s·(d(x) − ξ) away returns t_max at once.
/// Returns NaN when x or dx has a non-finite entry: no step is known to be safe, and callers
/// must stop (a NaN would otherwise vanish in std::min).
/// @param x stencil positions at t = 0 (12)
/// @param dx displacement (12)
/// @param thickness ξ ≥ 0, the distance the pair must never get below
/// @param s ∈ (0, 1), the fraction of the initial gap d(x) − ξ kept at the returned t (C-IPC
///        uses 0.1)
/// @param t_max upper bound on t (usually 1)
/// @param max_iterations cap on the advancement's iterations
/// @param stop_at no t above this is needed (e.g. the smallest step found so far among other
///        pairs): the advancement ends there. The result is exactly min(the result without
///        stop_at, stop_at), so a running minimum gives the same overall minimum in any order
///        (for motions whose gaps stay finite: one that overflows mid-way may give NaN unstopped
///        and stop_at stopped).
double additive_ccd_point_triangle(const Vec12& x, const Vec12& dx, double thickness, double s,
                                   double t_max, int max_iterations = kAccdMaxIterations,
                                   double stop_at = std::numeric_limits<double>::infinity());

/// As additive_ccd_point_triangle() for an edge–edge stencil (ea0, ea1, eb0, eb1).
double additive_ccd_edge_edge(const Vec12& x, const Vec12& dx, double thickness, double s,
                              double t_max, int max_iterations = kAccdMaxIterations,
                              double stop_at = std::numeric_limits<double>::infinity());

}  // namespace progsim
