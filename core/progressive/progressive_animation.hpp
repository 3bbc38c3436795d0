#pragma once
/// @file What a progressive animation driver offers its users (the CLI, benchmarks): a preview
/// stepped on level 0, finer levels animated over it, and every level's frames and records.
/// ProgressiveDynamics (shells, PD) and VolumetricDynamics (tet solids, VPD) implement it.
#include <memory>

#include "progressive/dynamic_records.hpp"
#include "progressive/level_refinement.hpp"
#include "scene/scene.hpp"
#include "sim/level_simulation.hpp"

namespace progsim {

/// A progressive animation. Level 0 is the coarsest.
class ProgressiveAnimation {
 public:
  virtual ~ProgressiveAnimation() = default;

  /// The method's name for summaries ("progressive dynamics", ...).
  virtual const char* method() const = 0;

  /// Discards every level's frames and starts the preview again from the initial state.
  virtual void restart() = 0;
  /// Replaces the scene (materials, effects, solver, prediction, penalty) for the preview from
  /// its current time on; meshes, levels and time step must stay. Error(wrong_call_order) once
  /// a finer level exists (restart() first); on Error nothing changed.
  virtual void update_scene(Scene scene) = 0;
  /// Sets the preview's velocities (3|V_0|, m/s) before its first step. Error(wrong_call_order)
  /// after it, Error(invalid_argument) on a wrong size or non-finite entry.
  virtual void set_preview_velocities(const Vector& velocities) = 0;
  /// One preview step on level 0 (Error(wrong_call_order) once a finer level exists).
  virtual StepRecord step_preview() = 0;
  /// Animates level level() + 1 over every previewed step (Error(out_of_range) at the finest,
  /// Error(wrong_call_order) before a preview step, Error(cancelled) when `progress` says stop).
  void refine(const RefineProgress& progress = nullptr) {
    refine_window(StepWindow{0, num_frames(level()) - 1}, progress);
  }
  /// Animates level level() + 1 over `window` of the previewed steps only, its frame 0 the
  /// coarser frame window.first refined vertically (PD §4.6): windows of the finest level can be
  /// animated apart and joined. Errors as refine(), and Error(invalid_argument) for a window
  /// outside the previewed steps, Error(wrong_call_order) above a level that is a window,
  /// Error(unsupported) for a window after frame 0 of a solid under contact.
  virtual void refine_window(StepWindow window, const RefineProgress& progress = nullptr) = 0;
  /// The finest level computed so far (0: only the preview).
  virtual int level() const = 0;
  /// The index of the finest level.
  virtual int finest() const = 0;
  virtual const Scene& scene() const = 0;
  /// The preview's simulation (level 0, live).
  virtual const LevelSimulation& preview() const = 0;
  /// Frames of a computed level (its steps + 1; frame 0 is the animation's frame
  /// record(level).first_step). Error(out_of_range) for others.
  virtual int num_frames(int level) const = 0;
  /// Positions and velocities (|V_level| × 3) of a frame of a computed level.
  virtual void read_frame(int level, int frame, Positions& positions,
                          Positions& velocities) const = 0;
  /// What a computed level did, step by step.
  virtual const DynamicLevelRecord& record(int level) const = 0;
  /// The surface faces of level `level` (its shell, or its solid's boundary) over its vertices.
  virtual const Faces& surface_faces(int level) const = 0;
  /// The direct baseline of level `level`: its mesh simulated alone from the initial state with
  /// its own energy (no proxy, no coarser trajectory), the scene's current settings.
  /// Error(out_of_range) for a level that does not exist.
  virtual std::unique_ptr<LevelSimulation> direct_level(int level) const = 0;
};

/// Progressive Dynamics for a scene of shells, its volumetric form (VPD) for a scene of solids.
/// Throws as the drivers' constructors do (a scene that mixes both: Error(unsupported)).
std::unique_ptr<ProgressiveAnimation> make_progressive_animation(Scene scene);

}  // namespace progsim
