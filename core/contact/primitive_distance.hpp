#pragma once
/// @file Unsigned distances between mesh primitives (point–triangle, edge–edge) on a uniform
/// 4-vertex stencil, the closest sub-primitive pair realising them, and the exact gradient and
/// Hessian of the squared distance for a fixed pair type (IPC, Li et al. 2020, §4).
///
/// Stencil vertex order: point–triangle (p, t0, t1, t2), edge–edge (ea0, ea1, eb0, eb1); the
/// stencil positions are stacked as x = (x0 y0 z0 x1 ... z3).
#include <Eigen/Core>
#include <array>

#include "common/types.hpp"

namespace progsim {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

/// Which sub-primitives realise the closest distance (IPC §4 distance types).
enum class DistanceType { point_point, point_edge, point_triangle, edge_edge };

/// The closest-distance realisation for a stencil: its type and the stencil vertices (0..3)
/// taking part, the point first:
///   point_point    (p, q)            distance ‖p − q‖
///   point_edge     (p, e0, e1)       distance from p to the line through e0, e1
///   point_triangle (p, t0, t1, t2)   distance from p to the plane through t0, t1, t2
///   edge_edge      (ea0, ea1, eb0, eb1)  distance between the two lines
/// Unused entries are −1.
struct ClosestPair {
  DistanceType type;
  std::array<int, 4> vertices;
};

/// Closest pair between the point p = x_0 and the closed triangle (x_1, x_2, x_3). A triangle
/// of (near) zero area is treated as its three edges.
ClosestPair classify_point_triangle(const Vec12& x);

/// Closest pair between the closed segments (x_0, x_1) and (x_2, x_3). (Nearly) parallel
/// segments yield a point_edge or point_point pair, never edge_edge.
ClosestPair classify_edge_edge(const Vec12& x);

/// Squared distance of the classified pair; for the pair returned by classify_*(x) it is the
/// unsigned squared distance between the two closed primitives.
double distance_squared(const Vec12& x, const ClosestPair& pair);

/// Gradient (12) and exact, unprojected Hessian (12 × 12) of distance_squared(x, pair) w.r.t. the
/// 12 stencil DOFs for the fixed pair type (zero rows/columns for non-participating vertices).
void distance_squared_derivatives(const Vec12& x, const ClosestPair& pair, Vec12& grad,
                                  Mat12& hess);

/// Gradient (12) of distance_squared(x, pair) alone, without the Hessian's cost: the
/// closest-point parameters are stationary, so ∂d²/∂x_k = 2 w_k r (envelope theorem) with w and
/// r of closest_point_weights(). Equal to distance_squared_derivatives()'s gradient up to
/// rounding.
void distance_squared_gradient(const Vec12& x, const ClosestPair& pair, Vec12& grad);

/// Weights w (4) with r = Σ_k w_k x_k the vector between the pair's closest points, pointing
/// from the second primitive (triangle, edge b) to the first (point, edge a); Σ_k w_k = 0 and
/// ‖r‖² = distance_squared(x, pair). E.g. point–triangle interior: (1, −β0, −β1, −β2) with β
/// the barycentric coordinates of p's projection; edge–edge: (1 − α, α, −(1 − β), −β).
Eigen::Vector4d closest_point_weights(const Vec12& x, const ClosestPair& pair);

/// Gradient of ‖a × b‖² w.r.t. (a, b): (2 b × (a × b), 2 (a × b) × a).
Vec6 cross_squared_norm_gradient(const Vec3& a, const Vec3& b);

/// ‖a × b‖² with its gradient (∂/∂a, ∂/∂b) and Hessian (6 × 6) w.r.t. (a, b).
double cross_squared_norm_derivatives(const Vec3& a, const Vec3& b, Vec6& grad, Mat6& hess);

}  // namespace progsim
