#pragma once
/// @file Local relaxation of the splits that contact stopped short during safe refinement (PSQ,
/// Zhang et al. 2023, §4.4.3): a few Newton iterations over the stuck vertices alone, pulling
/// them toward their prolonged targets against the contact barrier, so that they end as close
/// to the targets as contact allows and later splits do not start from collapsed patches.
#include <optional>
#include <vector>

#include "contact/contact_pair.hpp"
#include "solve/newton_solver.hpp"

namespace progsim {

/// Minimises ½‖x − x̂‖² (unit weights: the closest point to the targets) plus the contact
/// barrier over `mesh`, over the shell vertices `free` only, from `points` (|V_mesh| × 3,
/// collision-vertex positions; the rows of the free vertices change in place). Pairs already
/// within their offsets are accepted (ContactPotential::fit_offsets); every accepted step is
/// CCD-bounded, so nothing crosses.
/// @param targets (num_shell_vertices × 3) x̂ of the shell vertices
/// @param length length scale of the solver's tolerance (m)
/// Returns the Newton report.
NewtonReport relax_toward_targets(const CollisionMesh& mesh, const Positions& targets,
                                  Positions& points, const std::vector<int>& free, double dhat,
                                  const std::optional<GroundPlane>& ground, double length);

}  // namespace progsim
