#pragma once
/// @file A moment on a group of points as a couple of forces (zero net force).
#include <string>

#include "common/types.hpp"

namespace progsim {

/// Forces f_i (k × 3, N) at `points` (k × 3, m) with weights w_i > 0 (k) whose sum is zero and
/// whose moment about any point is exactly `moment` · a (N·m, a = axis / |axis|): the
/// least-squares distribution min Σ |f_i|²/w_i, f_i = w_i μ × d_i with d_i = p_i − c about the
/// weighted centroid c and I_c μ = M a, I_c = Σ w_i (|d_i|² 1 − d_i d_iᵀ) (the rigid-rotation
/// field of a body with inertia I_c). For a group in a plane normal to a this is the elastic
/// method for an eccentrically loaded bolt group, f_i = M w_i a × d_i / Σ w_j |d_j|² (Shigley's
/// Mechanical Engineering Design, 10th ed., eq. 8-57: F''_i = M r_i / Σ r_j²). Zero forces for
/// moment = 0. Throws Error(invalid_scene) prefixed by `where` when the points cannot carry the
/// moment (all on one line parallel to a, or a single point) or the axis is zero or not finite.
Positions couple_forces(const Positions& points, const Eigen::VectorXd& weights, const Vec3& axis,
                        double moment, const std::string& where);

}  // namespace progsim
