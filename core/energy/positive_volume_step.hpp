#pragma once
/// @file The longest step along which a tetrahedron keeps a positive volume (an inversion-free
/// line search, as Smith and Schaefer 2015 do for triangles and IPC, Li et al. 2020, for tets).
#include "common/types.hpp"

namespace progsim {

/// For edge matrices D (3×3, det D > 0) moving along dD, the largest α ∈ [0, 1] such that
/// det(D + t dD) > 0 for all t ∈ [0, α], shrunk by the factor 0.8 when a root of the cubic
/// det(D + t dD) lies in (0, 1] (so that no accepted state is arbitrarily close to flat).
/// 0 when det D ≤ 0; NaN when D or dD is not finite.
double positive_volume_step(const Mat3& d, const Mat3& dd);

}  // namespace progsim
