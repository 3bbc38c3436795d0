#pragma once
/// @file The shell prolongations of a hierarchy's levels: P^l_{l+1} to the next finer level
/// (PSQ eq. 7) and P^l straight to the finest (PSQ eqs. 8–9).
#include "hierarchy/mesh_hierarchy.hpp"
#include "hierarchy/shell_prolongation.hpp"

namespace progsim {

/// P^l: level `level` (< finest) to the finest level (PSQ eq. 9). Throws Error(out_of_range)
/// for a level that is not a coarse level of h.
ShellProlongation direct_prolongation(const MeshHierarchy& h, int level);

/// P^l_{l+1}: level `level` (< finest) to level + 1 (PSQ eq. 7). Throws as above.
ShellProlongation next_level_prolongation(const MeshHierarchy& h, int level);

}  // namespace progsim
