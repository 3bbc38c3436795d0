#include "progressive/level_refinement.hpp"

#include <string>

#include "common/error.hpp"
#include "progressive/consistency_projection.hpp"

namespace progsim {
namespace {

/// x̂ of a finer level's step t → t+1 from the coarser frames t and t+1 and the level's own xᵗ.
Vector predicted(DynamicsPrediction rule, const LevelTransfer& p, double h, const Vector& fine_now,
                 const Vector& coarse_now, const Vector& coarse_velocity_now,
                 const Vector& coarse_next) {
  switch (rule) {
    case DynamicsPrediction::velocity_only:  // PD++ / VPD eq. 2: x_{l+1}^t + h U v_l^t
      return fine_now + h * p.velocities(coarse_velocity_now);
    case DynamicsPrediction::prolonged_positions:  // PD eq. 5: P(x_l^t) + h U v_l^t
      return p.positions(coarse_now) + h * p.velocities(coarse_velocity_now);
    case DynamicsPrediction::per_frame:  // PSQ per frame (PD §4.3 fn. 3): P(x_l^{t+1})
      return p.positions(coarse_next);
  }
  return fine_now;
}

/// The targets of a finer level's step t → t+1: x̂ by `settings.prediction`, the consistency
/// penalty's P(x_l^{t+1}) and, per frame, the vertical refinement the step starts from.
StepTargets step_targets(const LevelSimulation& sim, const LevelTransfer& p,
                         const ProgressiveSettings& settings, double h, const Vector& coarse_now,
                         const Vector& coarse_velocity_now, const Vector& coarse_next) {
  StepTargets targets;
  targets.predicted = predicted(settings.prediction, p, h, sim.dofs(), coarse_now,
                                coarse_velocity_now, coarse_next);
  if (settings.consistency_weight > 0.0) targets.consistency = p.positions(coarse_next);
  if (settings.prediction == DynamicsPrediction::per_frame)
    targets.start =
        p.vertical ? p.vertical(coarse_next, targets.predicted, sim) : targets.predicted;
  return targets;
}

void check_per_frame(const LevelSimulation& sim, const LevelTransfer& p,
                     const ProgressiveSettings& settings) {
  if (settings.prediction == DynamicsPrediction::per_frame && !p.vertical && sim.contact())
    fail(Status::unsupported,
         "the per_frame prediction restarts every step from the coarser frame, which needs a safe "
         "vertical refinement under contact; this hierarchy (tets) has none");
}

}  // namespace

LevelStart window_start(const LevelSimulation& at_rest, const CoarserLevel& coarse,
                        const LevelTransfer& transfer, const StepWindow& window) {
  if (window.first == 0) return {};
  if (!transfer.vertical && at_rest.contact())
    fail(Status::unsupported,
         "a window starting after frame 0 starts from the coarser frame refined vertically, which "
         "needs a safe vertical refinement under contact; this hierarchy (tets) has none");
  Vector x, v;
  coarse.frames->read(window.first, x, v);
  const Vector target = transfer.positions(x);
  LevelStart start;
  start.positions = transfer.vertical ? transfer.vertical(x, target, at_rest) : target;
  start.steps_taken = window.first;
  start.fit_to_start = true;  // a refined state: offsets and strain limits fitted (PSQ §4.4)
  return start;
}

void animate_finer_level(LevelSimulation& sim, const CoarserLevel& coarse,
                         const LevelTransfer& transfer, const ProgressiveSettings& settings,
                         double time_step, const StepWindow& window, const RefineProgress& progress,
                         Trajectory& frames, DynamicLevelRecord& record) {
  check_per_frame(sim, transfer, settings);
  const int steps = window.last - window.first;
  Vector x_now, v_now, x_next, v_next;
  coarse.frames->read(window.first, x_now, v_now);
  sim.set_velocities(transfer.velocities(v_now));  // v_{l+1}^first = U v_l^first
  frames.append(sim.dofs(), sim.velocities());
  const ConsistencyProjection projection(*transfer.intrinsic, sim.model().vertex_masses,
                                         *coarse.masses);
  for (int t = window.first; t < window.last; ++t) {
    coarse.frames->read(t + 1, x_next, v_next);
    const StepRecord step =  // PD eq. 6
        sim.step(step_targets(sim, transfer, settings, time_step, x_now, v_now, x_next));
    frames.append(sim.dofs(), sim.velocities());
    const double deviation = step.motion ? com_deviation(step.motion->center_of_mass, record,
                                                         *coarse.preview, t, window.first)
                                         : 0.0;
    add_dynamic_step(record, step, deviation, projection.distance(sim.dofs(), x_next));
    const int done = t + 1 - window.first;
    if (progress && !progress(done, steps))
      fail(Status::cancelled, "refining level " + std::to_string(coarse.index) + " into level " +
                                  std::to_string(coarse.index + 1) + " was cancelled at step " +
                                  std::to_string(done) + " of " + std::to_string(steps));
    std::swap(x_now, x_next);
    std::swap(v_now, v_next);
  }
  record.terms = sim.term_totals();
}

}  // namespace progsim
