#pragma once
/// @file The levels a progressive animation has computed so far: the live preview (level 0) and,
/// per level, its frames (streamed to disk), its record and its masses. Both progressive
/// animation drivers (PD for shells, VPD for solids) keep their levels in one.
#include <functional>
#include <memory>
#include <vector>

#include "progressive/dynamic_records.hpp"
#include "progressive/level_refinement.hpp"
#include "progressive/trajectory.hpp"
#include "sim/level_simulation.hpp"

namespace progsim {

/// Levels 0 … level() of an animation whose finest level is `finest`.
class AnimatedLevels {
 public:
  explicit AnimatedLevels(int finest) : finest_(finest) {}

  /// Drops every level and starts again from `preview` (level 0) at its initial state.
  void restart(std::unique_ptr<LevelSimulation> preview);
  /// Sets the preview's initial velocities (3|V_0|, m/s). Throws Error(wrong_call_order) once a
  /// finer level exists or the preview has stepped, as LevelSimulation::set_velocities otherwise.
  void set_preview_velocities(const Vector& velocities);
  /// Gives the preview `preview_scene` (the level-0 form of `updated`) once `updated` may
  /// replace `current` mid-animation. Throws Error(wrong_call_order) once a finer level exists,
  /// Error(invalid_scene) for a quasistatic scene, Error(invalid_argument) for a new time step
  /// or new progressive levels (they fix the animation), and as validate_scene(); on Error
  /// nothing changed.
  void update_preview_scene(const Scene& current, const Scene& updated, const Scene& preview_scene);
  /// One preview step, recorded. Throws Error(wrong_call_order) once a finer level exists.
  StepRecord step_preview();
  /// Makes level level() + 1's simulation from a start (LevelStart{}: its initial state).
  using LevelFactory = std::function<std::unique_ptr<LevelSimulation>(LevelStart)>;
  /// Animates level level() + 1, made by `make`, over `window` of the previewed steps through
  /// `transfer` (window_start, animate_finer_level) and keeps it. Throws Error(out_of_range) at
  /// the finest level, Error(wrong_call_order) before a preview step or above a level that
  /// animates a window only, Error(invalid_argument) for a window outside the previewed steps,
  /// Error(cancelled) from `progress`; on Error nothing changed.
  void refine(const LevelFactory& make, const LevelTransfer& transfer,
              const ProgressiveSettings& settings, double time_step, StepWindow window,
              const RefineProgress& progress);
  /// Throws the errors refine() throws before any work.
  void check_refinable(const StepWindow& window) const;
  /// Throws Error(wrong_call_order), naming `what`, once a finer level exists.
  void check_preview_open(const char* what) const;

  int level() const { return static_cast<int>(trajectories_.size()) - 1; }
  LevelSimulation& preview() { return *preview_; }
  const LevelSimulation& preview() const { return *preview_; }
  int num_frames(int level) const;
  void read_frame(int level, int frame, Positions& positions, Positions& velocities) const;
  const DynamicLevelRecord& record(int level) const;

 private:
  /// Throws Error(out_of_range) unless level `level` has been computed.
  void check_level(int level) const;

  int finest_;
  std::unique_ptr<LevelSimulation> preview_;
  std::vector<Trajectory> trajectories_;
  std::vector<DynamicLevelRecord> records_;
  std::vector<Eigen::VectorXd> masses_;
};

}  // namespace progsim
