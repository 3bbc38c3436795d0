#include "progressive/scene_level_counts.hpp"

#include "hierarchy/mesh_hierarchy.hpp"

namespace progsim {

std::vector<int> scene_coarse_counts(const ProgressiveSettings& settings, int finest_vertices) {
  if (!settings.level_vertices.empty()) return settings.level_vertices;
  if (settings.coarse_levels == 0) return {};
  return geometric_level_counts(finest_vertices, settings.coarsening_ratio, settings.coarse_levels);
}

}  // namespace progsim
