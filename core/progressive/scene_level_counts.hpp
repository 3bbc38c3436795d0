#pragma once
/// @file How many vertices each coarse level of a scene's hierarchy gets.
#include <vector>

#include "scene/scene.hpp"

namespace progsim {

/// The coarse levels' vertex counts a scene's "progressive" section asks for, coarsest first:
/// its explicit level_vertices, else coarse_levels counts shrinking from `finest_vertices` by
/// coarsening_ratio (geometric_level_counts); empty for a single (direct) level. For a shell,
/// `finest_vertices` counts its mesh's vertices; for a solid, its boundary's.
std::vector<int> scene_coarse_counts(const ProgressiveSettings& settings, int finest_vertices);

}  // namespace progsim
