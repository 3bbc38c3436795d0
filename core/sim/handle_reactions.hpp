#pragma once
/// @file The forces and moments the handles' supports apply.
#include <vector>

#include "common/types.hpp"
#include "sim/handle_targets.hpp"
#include "sim/step_record.hpp"

namespace progsim {

/// Per handle of `handles`, its reaction at state x (3|V|) from the full gradient (3|V|, fixed
/// DOFs included) of the objective the step minimised. At a solution every free DOF has
/// ∂E/∂x = 0, so a prescribed DOF's ∂E/∂x is the force its support adds to keep it there
/// (Lagrange multiplier of x_d = target). A rotation support's carried DOFs count too: their
/// forces sum to zero along its free translation and give the moment that turns the group.
/// Handles without a vertex on the level read zero.
std::vector<HandleReaction> handle_reactions(const HandleTargets& handles, const Vector& x,
                                             const Vector& gradient);

}  // namespace progsim
