#pragma once
/// @file Mollifier of the edge–edge barrier (IPC, Li et al. 2020, §4.3, eq. 23): smoothly turns
/// the barrier off as two edges become parallel, where the edge–edge distance type changes
/// non-smoothly.
#include "contact/primitive_distance.hpp"

namespace progsim {

/// Threshold ε_x = 10⁻³ ‖ēa‖²‖ēb‖² from the rest positions of an edge–edge stencil
/// (ea0, ea1, eb0, eb1) (12).
double mollifier_threshold(const Vec12& rest_x);

/// m(x) = −c²/ε_x² + 2c/ε_x for c = ‖ea × eb‖² < ε_x, else 1 (ea = ea1 − ea0, eb = eb1 − eb0),
/// at edge–edge stencil positions x (12).
double mollifier(const Vec12& x, double eps_x);

/// m(x) with its gradient (12) (zero where c ≥ ε_x), without the Hessian's cost.
double mollifier_gradient(const Vec12& x, double eps_x, Vec12& grad);

/// m(x) with its gradient (12) and exact Hessian (12 × 12) w.r.t. the stencil DOFs (both zero
/// where c ≥ ε_x).
void mollifier_derivatives(const Vec12& x, double eps_x, double& m, Vec12& grad, Mat12& hess);

}  // namespace progsim
