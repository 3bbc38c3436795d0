#pragma once
/// @file How far one state of a mesh is from another, as the accuracy reports measure it.
#include "common/types.hpp"

namespace progsim {

/// Per-vertex distances ‖x_i − reference_i‖ (same shapes): root mean square and maximum, each
/// divided by `length` (the finest rest shape's bounding-box diagonal, DESIGN.md metrics).
struct StateDistance {
  double rms = 0.0, max = 0.0;
};

/// The distance of x to reference over `length`. Throws Error(invalid_argument) on different
/// shapes or a length that is not positive.
StateDistance state_distance(const Positions& x, const Positions& reference, double length);

}  // namespace progsim
