#pragma once
/// @file Volumetric Progressive Dynamics (VPD, 2025, §3.2–3.3): the progressive animation of a
/// tetrahedral solid. Each level is simulated with its own elastics (VPD §3.2: coarse levels are
/// not proxies of the finest), the preview on the coarsest; every finer level is animated over
/// the previewed span with its steps predicted from the coarser trajectory through the
/// barycentric prolongation W (VPD eq. 2) and the optional consistency penalty (VPD eq. 4).
#include <memory>
#include <vector>

#include "hierarchy/tet_hierarchy.hpp"
#include "progressive/animated_levels.hpp"
#include "progressive/dynamic_records.hpp"
#include "progressive/progressive_animation.hpp"
#include "progressive/trajectory.hpp"
#include "scene/scene.hpp"
#include "sim/level_simulation.hpp"

namespace progsim {

/// The VPD driver. Level 0 is the coarsest.
class VolumetricDynamics final : public ProgressiveAnimation {
 public:
  /// `scene`: dynamic, one volumetric body whose mesh is `hierarchy`'s finest level. Throws
  /// Error(invalid_scene) for a quasistatic scene, Error(invalid_argument) if the hierarchy does
  /// not match the body or has fewer than two levels, Error(unsupported) for several bodies or
  /// a handle or load that lists vertices by index, Error(invalid_scene) for one whose box
  /// holds no vertex of some level, and as validate_scene(). Handles and loads select each
  /// level's vertices by their box (Handle::region): the levels share no vertices.
  VolumetricDynamics(Scene scene, std::shared_ptr<const TetHierarchy> hierarchy);
  ~VolumetricDynamics();
  VolumetricDynamics(const VolumetricDynamics&) = delete;
  VolumetricDynamics& operator=(const VolumetricDynamics&) = delete;

  /// Sets the preview's velocities (3|V_0|, m/s) before its first step. Throws
  /// Error(wrong_call_order) after it, Error(invalid_argument) on a wrong size or non-finite entry.
  void set_preview_velocities(const Vector& velocities) override {
    levels_.set_preview_velocities(velocities);
  }
  /// Discards every level's frames and starts the preview again from the initial state.
  void restart() override { levels_.restart(make_level(0)); }
  /// Replaces the scene for the preview from its current time on (ProgressiveAnimation); the
  /// body's mesh must stay the hierarchy's finest level. Also throws as the constructor does.
  void update_scene(Scene scene) override;
  /// One preview step on level 0. Throws Error(wrong_call_order) once a finer level exists
  /// (restart() first).
  StepRecord step_preview() override { return levels_.step_preview(); }
  /// Animates level level() + 1 over every previewed step (VPD eq. 2 with
  /// scene.progressive.prediction; the penalty with scene.progressive.consistency_weight > 0),
  /// from its rest shape with the prolonged initial velocities. Throws Error(out_of_range) at the
  /// finest level, Error(wrong_call_order) before any preview step, Error(cancelled) if
  /// `progress` says stop; on Error nothing changed.
  void refine_window(StepWindow window, const RefineProgress& progress = nullptr) override;

  const char* method() const override { return "volumetric progressive dynamics"; }
  /// The finest level computed so far (0: only the preview).
  int level() const override { return levels_.level(); }
  int finest() const override { return static_cast<int>(hierarchy_->levels.size()) - 1; }
  const TetHierarchy& hierarchy() const { return *hierarchy_; }
  std::shared_ptr<const TetHierarchy> shared_hierarchy() const { return hierarchy_; }
  const Scene& scene() const override { return scene_; }
  /// The scene of level `level`: the scene with its body's mesh and tets replaced by the level's,
  /// and its handles' and loads' vertices those their boxes hold there.
  Scene level_scene(int level) const { return level_scene(scene_, level); }
  /// The boundary faces of tet level `level`.
  const Faces& surface_faces(int level) const override { return surface_faces_.at(level); }
  /// Level `level`'s tets alone with their own elastics (the direct baseline).
  std::unique_ptr<LevelSimulation> direct_level(int level) const override;
  /// Frames of a computed level (steps + 1). Throws Error(out_of_range) otherwise.
  int num_frames(int level) const override { return levels_.num_frames(level); }
  /// Positions and velocities (|V_level| × 3) of a frame. Throws Error(out_of_range).
  void read_frame(int level, int frame, Positions& positions,
                  Positions& velocities) const override {
    levels_.read_frame(level, frame, positions, velocities);
  }
  /// What a computed level did, step by step. Throws Error(out_of_range).
  const DynamicLevelRecord& record(int level) const override { return levels_.record(level); }
  /// The preview's simulation (level 0, live).
  const LevelSimulation& preview() const override { return levels_.preview(); }

 private:
  /// `scene` with its body's mesh and tets replaced by level `level`'s.
  Scene level_scene(const Scene& scene, int level) const;
  /// Level `level`'s simulation from `start` (its initial state by default).
  std::unique_ptr<LevelSimulation> make_level(int level, LevelStart start = {}) const;

  Scene scene_;
  std::shared_ptr<const TetHierarchy> hierarchy_;
  std::vector<Faces> surface_faces_;  // per level, tet_boundary_faces
  AnimatedLevels levels_;
};

/// The tet hierarchy of a scene's one volumetric body (build_tet_hierarchy): coarse boundary
/// vertex counts from scene.progressive (level_vertices, or coarse_levels coarsened by
/// coarsening_ratio from the body's boundary vertex count; neither: the single finest level).
/// Throws as build_tet_hierarchy does; Error(unsupported) unless the scene has one solid body.
TetHierarchy build_scene_tet_hierarchy(const Scene& scene, HierarchyProgress progress = nullptr,
                                       void* user = nullptr);

}  // namespace progsim
