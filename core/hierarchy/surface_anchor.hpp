#pragma once
/// @file Where a point of a finer mesh sits on a coarser one: a coarse face and barycentric
/// weights in it (the intrinsic map of PSQ §4.3, after Liu et al. 2021).
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// A point on a coarse mesh: face `face` (a row of the coarse Faces) and barycentric weights
/// of its three corners (non-negative, summing to 1).
struct SurfaceAnchor {
  int face = -1;
  Vec3 weights = Vec3::Zero();
};

/// How far anchor weights may be below 0 or their sum off 1 (round-off of the tracking).
constexpr double kAnchorWeightTolerance = 1e-9;

/// One anchor per vertex of the finer mesh.
using SurfaceAnchors = std::vector<SurfaceAnchor>;

}  // namespace progsim
