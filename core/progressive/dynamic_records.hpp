#pragma once
/// @file What each level of a progressive animation did, step by step (Progressive Dynamics and
/// its volumetric form): the records and metrics both drivers and the direct baseline keep.
#include <functional>
#include <optional>
#include <vector>

#include "sim/level_simulation.hpp"

namespace progsim {

/// One step of one level of a progressive animation.
struct DynamicStepRecord {
  int step = 0;               ///< 1-based
  double time = 0.0;          ///< s, after the step
  int newton_iterations = 0;  ///< this step's, script rounds included
  bool converged = false;     ///< the step's Newton solve met the tolerance
  double seconds = 0.0;       ///< wall time of the step
  MotionRecord motion;        ///< kinetic energy, centre of mass, continuity (PD++)
  /// ‖(CoM_lᵗ − CoM_l⁰) − (CoM_0ᵗ − CoM_0⁰)‖ (m): how far the level's centre of mass has moved
  /// away from the preview's since the start (PD Figs. 9, 19; each level's own start is
  /// subtracted, since decimation moves the rest centre of mass by a little); 0 on the preview.
  double com_deviation = 0.0;
  /// VPD App. C eq. 19 (PD++'s consistency): ‖Π x_l − x_{l−1}‖_{M_{l−1}} (m, mass-weighted RMS)
  /// with Π = (UᵀMU)⁻¹UᵀM the mass-weighted least-squares projection through the intrinsic
  /// part U of P_l^{l−1}; 0 on the preview.
  double consistency = 0.0;
  std::optional<ContactStats> contact;  ///< with contact: this step's counters
  std::optional<double> max_stretch;    ///< with a strain limit: the largest stretch after it
  std::optional<WindRecord> wind;       ///< with wind: the wind and its force after it
  /// Per handle, what its support applies (StepRecord::reactions; empty on the preview).
  std::vector<HandleReaction> reactions;
};

/// One level of a progressive animation: its size, work and per-step records.
struct DynamicLevelRecord {
  int vertices = 0;
  int first_step = 0;  ///< the level's frame 0 is the animation's frame first_step (a window)
  Vec3 start_center_of_mass = Vec3::Zero();  ///< at frame 0 (m)
  double seconds = 0.0;                      ///< wall time of the level's steps
  int newton_iterations = 0;                 ///< over its steps
  int converged_steps = 0;                   ///< steps whose solve met the tolerance
  std::vector<TermStats> terms;              ///< counters per term over the level's steps
  std::vector<DynamicStepRecord> steps;      ///< per step, in order (frame k + 1 after step k)
};

/// Adds a step's outcome to `record` with its metrics against other trajectories (the
/// centre-of-mass deviation and the consistency; 0 where there is none), and counts its work.
/// The direct baseline records its levels so too (progsim accuracy).
void add_dynamic_step(DynamicLevelRecord& record, const StepRecord& step, double com_deviation,
                      double consistency);

/// An empty record of the level `sim` animates, from its state at frame 0.
DynamicLevelRecord start_record(const LevelSimulation& sim);

/// DynamicStepRecord::com_deviation of a step of `level` ending with centre of mass `com`
/// against step `t` (0-based) of `reference`: how far each moved since frame `first` (the
/// level's first frame; `reference`'s frame `first`).
double com_deviation(const Vec3& com, const DynamicLevelRecord& level,
                     const DynamicLevelRecord& reference, int t, int first = 0);

/// Called during refine() after each step with (steps done, steps in all); returning false
/// cancels the refinement.
using RefineProgress = std::function<bool(int done, int total)>;

}  // namespace progsim
