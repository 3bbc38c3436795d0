#pragma once
/// @file `progsim run` on a dynamic scene with coarse levels: Progressive Dynamics end to end.
#include "cli/run_command.hpp"
#include "scene/scene.hpp"

namespace progsim::cli {

/// PD (Zhang, James and Kaufman 2024, Alg. 1): the scene's steps previewed on level 0, then
/// each finer level animated over them (ProgressiveDynamics::refine), with a progress bar per
/// level. Writes level_<l>/frame_NNNNN.obj (every output_every steps and the last, on the
/// level's own mesh), obstacles_NNNNN.obj (the obstacles at their scripted pose, the same on
/// every level), steps.jsonl (one line per level and step), the plots of
/// write_dynamics_plots and summary.json (per level: vertices, wall time, Newton iterations,
/// converged steps, centre-of-mass deviation from the preview, continuity, consistency),
/// written last; prints the level table. Returns as run_run_command.
int run_progressive_dynamics(Scene scene, const RunCommand& options);

}  // namespace progsim::cli
