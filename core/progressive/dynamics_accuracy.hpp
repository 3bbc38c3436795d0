#pragma once
/// @file Progressive Dynamics (PD for shells, VPD for solids) against direct simulation at every
/// level (PD Fig. 19): the same steps animated progressively (preview, then each level refined)
/// and directly on each level alone, with each level's centre-of-mass trajectory against its
/// method's coarsest level.
#include <string>
#include <vector>

#include "progressive/accuracy.hpp"
#include "progressive/progressive_animation.hpp"
#include "scene/scene.hpp"

namespace progsim {

/// Both animations of a dynamic scene, level by level (0 = coarsest).
struct DynamicsAccuracyReport {
  std::string scene;
  std::string method;  ///< the progressive method ("progressive dynamics", ...)
  int steps = 0;
  double time_step = 0.0;
  Vec3 up = Vec3::UnitY();  ///< against gravity: "height" in the plots
  /// Progressive levels: com_deviation from the preview (level 0), consistency against the
  /// next coarser level.
  std::vector<DynamicLevelRecord> progressive;
  /// Direct levels (LevelSimulation on the level's mesh with the level's own energy, no
  /// proxy): com_deviation from the direct coarsest level; no consistency.
  std::vector<DynamicLevelRecord> direct;
};

/// Animates the scene (dynamic, with coarse levels; Error(invalid_scene) otherwise) over its
/// steps progressively and then directly on every level. `progress` is told each phase and
/// step as in run_accuracy and can cancel (Error(cancelled)).
DynamicsAccuracyReport run_dynamics_accuracy(const Scene& scene,
                                             AccuracyProgress progress = nullptr,
                                             void* user = nullptr);

/// The CSV text: one line per method and level (vertices, seconds, Newton iterations,
/// converged steps, centre-of-mass deviation max and mean, mean continuity, max consistency).
std::string dynamics_accuracy_csv(const DynamicsAccuracyReport& report);

/// The CSV text: one line per method, level and step (time, kinetic energy, centre of mass,
/// deviation).
std::string dynamics_trajectory_csv(const DynamicsAccuracyReport& report);

/// Markdown: the per-level table of both methods and the largest deviation of each.
std::string dynamics_accuracy_markdown(const DynamicsAccuracyReport& report);

/// Writes accuracy.csv, trajectories.csv, accuracy.md and the plots of write_dynamics_plots
/// (both methods) into `dir` (created). Throws Error(io_error) naming a file not written.
void write_dynamics_accuracy_report(const DynamicsAccuracyReport& report, const std::string& dir);

/// Whether every step of both finest levels met the Newton tolerance.
bool finest_levels_converged(const DynamicsAccuracyReport& report);

}  // namespace progsim
