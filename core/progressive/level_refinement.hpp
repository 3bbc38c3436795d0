#pragma once
/// @file Animating a finer level over a coarser level's trajectory (PD eqs. 5–6, Alg. 1 lines
/// 7–14; PD++ / VPD eq. 2 velocity-only prediction; VPD eq. 4 consistency penalty): the loop both
/// progressive animation drivers run, shells through the shell prolongation, solids through W.
#include <functional>

#include "hierarchy/prolongation.hpp"
#include "progressive/dynamic_records.hpp"
#include "progressive/trajectory.hpp"
#include "scene/scene.hpp"
#include "sim/level_simulation.hpp"

namespace progsim {

/// How a finer level sees the coarser one: P (positions, DOFs → DOFs), U (velocities, DOFs →
/// DOFs), U as a matrix (for the consistency metric, VPD App. C eq. 19) and, for PSQ per frame,
/// the vertical refinement of a coarser frame.
struct LevelTransfer {
  /// A coarser frame (DOFs) refined toward `target` = P(frame) on the finer level, free of
  /// crossings with it and its surroundings in `finer` (PSQ §4.4's safe refinement).
  using Vertical = std::function<Vector(const Vector& frame, const Vector& target,
                                        const LevelSimulation& finer)>;
  std::function<Vector(const Vector&)> positions;
  std::function<Vector(const Vector&)> velocities;
  const ProlongationMatrix* intrinsic = nullptr;
  Vertical vertical;  ///< empty: none (then per_frame takes P(frame) and refuses contact)
};

/// The steps of the coarser level's span a finer level animates: from frame `first` to frame
/// `last` (0 <= first < last <= the previewed steps). A window that starts after
/// frame 0 starts from the coarser frame `first` refined vertically (LevelTransfer::vertical,
/// PD §4.6's vertical warm start), so windows can be animated apart (on several machines).
struct StepWindow {
  int first = 0;
  int last = 0;
};

/// The coarser level an animation refines: its frames, its masses and the preview's record
/// (the reference of the centre-of-mass deviation).
struct CoarserLevel {
  const Trajectory* frames = nullptr;
  const Eigen::VectorXd* masses = nullptr;
  const DynamicLevelRecord* preview = nullptr;
  int index = 0;  ///< the coarser level's number, for messages
};

/// Where a finer level's animation of `window` (checked: 0 ≤ first < last) starts: empty for
/// frame 0 (the level's initial state); else the coarser frame `first` refined vertically
/// toward P(x_l^first) among the surroundings of `at_rest` (the finer level at its initial
/// state), at the time of frame `first`. Throws Error(unsupported) under contact without a
/// vertical refinement (solids).
LevelStart window_start(const LevelSimulation& at_rest, const CoarserLevel& coarse,
                        const LevelTransfer& transfer, const StepWindow& window);

/// Animates `sim` (the finer level at the state of frame window.first, window checked) over the
/// window's steps of `coarse`: its
/// velocities start as U v_l^first, each step's x̂ follows `prediction` and, with a consistency
/// weight, the penalty pulls toward P(x_l^{t+1}). With the per_frame prediction each step starts
/// from the vertical refinement of x_l^{t+1} instead of the level's own xᵗ (PSQ per frame, PD
/// §4.3 fn. 3). Appends every frame to `frames` and every step to `record`. Throws
/// Error(cancelled) when `progress` returns false, Error(unsupported) for per_frame with contact
/// and no vertical refinement (solids).
void animate_finer_level(LevelSimulation& sim, const CoarserLevel& coarse,
                         const LevelTransfer& transfer, const ProgressiveSettings& settings,
                         double time_step, const StepWindow& window, const RefineProgress& progress,
                         Trajectory& frames, DynamicLevelRecord& record);

}  // namespace progsim
