#pragma once
/// @file Progressive Dynamics (PD, Zhang, James and Kaufman 2024, §4 and Algorithm 1, with
/// PD++'s velocity-only prolongation and consistency penalty as VPD §3.2 describes them): a
/// coarse animation preview, then each finer level animated over the previewed span, its
/// steps predicted from the coarser level's trajectory.
#include <functional>
#include <memory>
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"
#include "hierarchy/shell_prolongation.hpp"
#include "progressive/animated_levels.hpp"
#include "progressive/dynamic_records.hpp"
#include "progressive/level_operators.hpp"
#include "progressive/progressive_animation.hpp"
#include "progressive/trajectory.hpp"
#include "scene/scene.hpp"
#include "sim/level_simulation.hpp"

namespace progsim {

/// The Progressive Dynamics driver. Level 0 is the coarsest. The preview animates level 0 step
/// by step (PD eq. 4: the proxy energy, each step solved to the scene's tolerance); refine()
/// then animates the next level over every previewed step (PD eqs. 5–6, Alg. 1 lines 7–14).
/// Every level's frames are streamed to disk (Trajectory).
class ProgressiveDynamics final : public ProgressiveAnimation {
 public:
  /// Builds the scene's hierarchy as ProgressiveSimulation does, or uses `hierarchy` (built
  /// from the scene's merged bodies with its handles as vertex groups). Throws
  /// Error(invalid_scene) for a quasistatic scene and as ProgressiveSimulation's constructor.
  explicit ProgressiveDynamics(Scene scene,
                               std::shared_ptr<const MeshHierarchy> hierarchy = nullptr,
                               HierarchyProgress progress = nullptr, void* user = nullptr);
  ~ProgressiveDynamics();
  ProgressiveDynamics(const ProgressiveDynamics&) = delete;
  ProgressiveDynamics& operator=(const ProgressiveDynamics&) = delete;

  /// One preview step on level 0; its frame is appended to level 0's trajectory. Throws
  /// Error(wrong_call_order) once a finer level has been computed (restart() first).
  const char* method() const override { return "progressive dynamics"; }
  StepRecord step_preview() override;
  /// Animates level level() + 1 over every previewed step: its first frame is the level's
  /// initial state (its rest shape, the prolonged initial velocities: P recovers rest shapes,
  /// so this is P(x_l^0), crossing-free as every level of the hierarchy is), and each step's
  /// x̂ is predicted from the coarser trajectory (scene.progressive.prediction) with the
  /// optional consistency penalty. Throws Error(out_of_range) at the finest level,
  /// Error(wrong_call_order) before any preview step, Error(cancelled) if `progress` says stop;
  /// on Error nothing changed.
  void refine_window(StepWindow window, const RefineProgress& progress = nullptr) override;
  /// Discards every level's frames and starts the preview again from the initial state (after
  /// update_scene(), to preview a variation).
  void restart() override;
  /// Replaces the scene (materials, loads, effects, solver, prediction, penalty) for the
  /// preview from its current time on; the meshes, handles' vertex sets, levels and time step
  /// must stay. Throws Error(wrong_call_order) once a finer level has been computed (restart()
  /// first), Error(invalid_argument / invalid_scene) on a bad scene; on Error nothing changed.
  void update_scene(Scene scene) override;
  /// Sets the preview's velocities (3|V_0|, m/s) before its first step. Throws
  /// Error(wrong_call_order) after it, Error(invalid_argument) on a wrong size or non-finite
  /// entry.
  void set_preview_velocities(const Vector& velocities) override;

  /// The finest level computed so far (0: only the preview).
  int level() const override { return levels_.level(); }
  int finest() const override { return hierarchy_->finest(); }
  const MeshHierarchy& hierarchy() const { return *hierarchy_; }
  std::shared_ptr<const MeshHierarchy> shared_hierarchy() const { return hierarchy_; }
  const Scene& scene() const override { return scene_; }
  /// Frames of level `level` (steps + 1: frame 0 is the initial state). Throws
  /// Error(out_of_range) for a level that does not exist or has not been computed.
  int num_frames(int level) const override { return levels_.num_frames(level); }
  /// Positions and velocities (|V_level| × 3) of frame `frame` of level `level`. Throws
  /// Error(out_of_range) for a level or frame not computed.
  void read_frame(int level, int frame, Positions& positions,
                  Positions& velocities) const override {
    levels_.read_frame(level, frame, positions, velocities);
  }
  /// What level `level` did, step by step. Throws Error(out_of_range) as num_frames().
  const DynamicLevelRecord& record(int level) const override { return levels_.record(level); }
  /// The preview's simulation (level 0, live).
  const LevelSimulation& preview() const override { return levels_.preview(); }
  /// The faces of hierarchy level `level`'s rest mesh.
  const Faces& surface_faces(int level) const override {
    return hierarchy_->levels.at(level).rest.faces;
  }
  /// Level `level`'s mesh alone with its own energy (the direct baseline, PD Fig. 19).
  std::unique_ptr<LevelSimulation> direct_level(int level) const override;

 private:
  /// Level `level` at its initial state, solved with the scene's own solver (PD solves each
  /// step to the tolerance, unlike PSQ's capped previews): the proxy energy below the finest
  /// level, the consistency penalty above the coarsest.
  /// Level `level`'s simulation from `start` (its initial state by default).
  std::unique_ptr<LevelSimulation> make_level(int level, LevelStart start = {}) const;

  Scene scene_;
  std::shared_ptr<const MeshHierarchy> hierarchy_;
  std::unique_ptr<const LevelOperators> operators_;
  AnimatedLevels levels_;
};

}  // namespace progsim
