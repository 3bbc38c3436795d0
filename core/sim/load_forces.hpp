#pragma once
/// @file The forces of a scene's point and line loads on one level's vertices.
#include <vector>

#include "energy/dead_loads.hpp"
#include "energy/follower_loads.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "scene/scene.hpp"
#include "sim/shell_model.hpp"

namespace progsim {

/// The full forces of each of scene.loads on `model` (the scene's own merged mesh), in order:
/// the total force spread by the load's distribution (Σ_i f_i = F for mass and area) plus its
/// moment as a couple with the same weights (couple_forces), at the rest positions. A group
/// lists each vertex once. Precondition: validate_scene(scene) passed.
std::vector<VertexForces> load_forces(const Scene& scene, const ShellModel& model);

/// The normal (follower) part of each of scene.loads on `model`, in order: the normal force
/// spread by the load's distribution (Σ_i a_i = N for mass and area); empty for loads without
/// one.
std::vector<NormalLoad> normal_loads(const Scene& scene, const ShellModel& model);

/// Whether any of the scene's loads has a normal (follower) force.
bool has_follower_loads(const Scene& scene);

/// The loads moved to level `level` of `hierarchy` (built from the model load_forces used):
/// f_l = Uᵀ f_L with U the intrinsic map to the finest level (hierarchy.to_finest, PSQ eq. 9),
/// the virtual-work-consistent restriction of the prolongation's linear part. It keeps each
/// load's net force exactly and its moment up to the anchors' distance from the finest
/// vertices. Level `level` = finest: the forces as given.
std::vector<VertexForces> restrict_loads(const std::vector<VertexForces>& loads,
                                         const MeshHierarchy& hierarchy, int level);

}  // namespace progsim
