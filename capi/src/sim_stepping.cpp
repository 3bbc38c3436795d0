// ps_sim_*: preview steps, refinement and reading results per level.
#include <limits>
#include <string>

#include "handles.hpp"
#include "mesh/mesh_io.hpp"

namespace progsim::capi {
namespace {

/// Positions of a level, range-checked first: see ProgressiveSimulation::positions, or a
/// progressive animation's last frame of the level.
Positions level_positions(const ps_sim& sim, int32_t level) {
  level_mesh(*sim.hierarchy, level);  // range check with the ABI's message
  if (!sim.animation) return sim.simulation->positions(level);
  Positions positions, velocities;
  sim.animation->read_frame(level, sim.animation->num_frames(level) - 1, positions, velocities);
  return positions;
}

/// One step at the current level (the preview of a progressive animation); throws
/// ApiError(PS_ERROR_NUMERICAL) if it produced non-finite positions.
void step_once(ps_sim& sim) {
  const StepRecord step = sim.animation ? sim.animation->step_preview() : sim.simulation->step();
  const Vector& x =
      sim.animation ? sim.animation->preview().dofs() : sim.simulation->current().dofs();
  if (!x.allFinite())
    api_fail(PS_ERROR_NUMERICAL,
             "step " + std::to_string(step.step) + " produced non-finite positions");
}

/// Whether the progress callback (if any) asks to cancel.
bool cancelled(const ps_sim& sim, int32_t done, int32_t total, const char* phase) {
  return sim.progress && sim.progress(sim.progress_user_data, done, total, phase) != 0;
}

/// Calls the progress callback; a non-zero answer cancels.
void report_progress(const ps_sim& sim, int32_t done, int32_t total, const char* phase) {
  if (cancelled(sim, done, total, phase))
    api_fail(PS_ERROR_CANCELLED, std::string("cancelled by the progress callback during ") + phase +
                                     " after " + std::to_string(done) + " of " +
                                     std::to_string(total));
}

/// The ABI's copy of a level's refinement statistics.
ps_refinement_stats refinement_stats(const SafeRefinementStats& s) {
  return ps_refinement_stats{
      s.batches,          s.splits,           s.random_directions,     s.rounds,
      s.stopped_vertices, s.relaxed_vertices, s.relaxation_iterations, s.inside_pairs,
      s.reached,          s.min_gap};
}

/// The ABI's copy of a level's strain correction.
ps_strain_correction_stats strain_correction_stats(const StrainCorrectionStats& s) {
  return ps_strain_correction_stats{s.strained_faces,    s.over_limit_faces,
                                    s.newton_iterations, s.moved_coarse_vertices ? 1 : 0,
                                    s.stretch_before,    s.stretch_after};
}

}  // namespace
}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API int32_t ps_sim_step_preview(ps_sim* sim, int32_t steps) {
  return guarded(error_slot(sim), "ps_sim_step_preview", [&] {
    require_idle(sim);
    if (steps < 1)
      api_fail(PS_ERROR_INVALID_ARGUMENT, "steps = " + std::to_string(steps) + " must be >= 1");
    const BusyGuard busy(*sim);
    for (int32_t s = 0; s < steps; ++s) {
      step_once(*sim);
      report_progress(*sim, s + 1, steps, "preview");
    }
  });
}

PS_API int32_t ps_sim_refine(ps_sim* sim) {
  return guarded(error_slot(sim), "ps_sim_refine", [&] {
    require_idle(sim);
    const BusyGuard busy(*sim);
    if (sim->animation) {  // cancelling makes the core throw Error(cancelled), nothing changed
      sim->animation->refine(
          [&](int done, int total) { return !cancelled(*sim, done, total, "refine"); });
      return;
    }
    report_progress(*sim, 0, 1, "refine");
    sim->simulation->refine();
    report_progress(*sim, 1, 1, "refine");
  });
}

PS_API int32_t ps_sim_refine_window(ps_sim* sim, int32_t first_step, int32_t last_step) {
  return guarded(error_slot(sim), "ps_sim_refine_window", [&] {
    require_idle(sim);
    ProgressiveAnimation& animation = animation_driver(*sim);
    const BusyGuard busy(*sim);
    animation.refine_window(StepWindow{first_step, last_step}, [&](int done, int total) {
      return !cancelled(*sim, done, total, "refine");
    });
  });
}

PS_API int32_t ps_sim_settle(ps_sim* sim, int32_t max_solves, int32_t* equilibrium) {
  return guarded(error_slot(sim), "ps_sim_settle", [&] {
    require_idle(sim);
    ProgressiveSimulation& psq = quasistatic_driver(*sim);
    const BusyGuard busy(*sim);
    const bool reached = psq.settle_to_equilibrium(
        max_solves, [&](int done) { report_progress(*sim, done, max_solves, "settle"); });
    if (equilibrium) *equilibrium = reached ? 1 : 0;
  });
}

PS_API int32_t ps_sim_current_level(const ps_sim* sim, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_current_level", [&] {
    require_idle(sim);
    require(out, "out");
    *out = sim->animation ? sim->animation->level() : sim->simulation->level();
  });
}

PS_API int32_t ps_sim_get_positions(const ps_sim* sim, int32_t level, double* out, size_t capacity,
                                    size_t* count) {
  return guarded(error_slot(sim), "ps_sim_get_positions", [&] {
    require_idle(sim);
    const Positions positions = level_positions(*sim, level);
    copy_out(positions.data(), static_cast<size_t>(positions.size()), out, capacity, count);
  });
}

PS_API int32_t ps_sim_write_mesh(const ps_sim* sim, int32_t level, const char* path) {
  return guarded(error_slot(sim), "ps_sim_write_mesh", [&] {
    require_idle(sim);
    require(path, "path");
    TriangleMesh mesh;
    mesh.vertices = level_positions(*sim, level);
    mesh.faces = level_mesh(*sim->hierarchy, level).faces;
    write_mesh(path, mesh);
  });
}

PS_API int32_t ps_sim_get_level_stats(const ps_sim* sim, int32_t level, ps_level_stats* out) {
  return guarded(error_slot(sim), "ps_sim_get_level_stats", [&] {
    require_idle(sim);
    require(out, "out");
    const ProgressiveSimulation& psq = quasistatic_driver(*sim);
    level_mesh(*sim->hierarchy, level);  // range check
    const LevelRecord& r = psq.records()[level];
    ps_level_stats stats{};
    stats.level = level;
    stats.steps = r.steps;
    stats.newton_iterations = r.newton_iterations;
    stats.converged_steps = r.converged_solves;
    stats.seconds = r.solve_seconds;
    stats.energy = r.energy;
    stats.gradient_norm = r.gradient_norm;
    stats.simulated_time = r.simulated_time;
    const std::optional<StateDistance> error = psq.error_against_finest(level);
    stats.error_rms = error ? error->rms : std::numeric_limits<double>::quiet_NaN();
    stats.error_max = error ? error->max : std::numeric_limits<double>::quiet_NaN();
    stats.settles = r.settles;
    stats.refine_seconds = r.refine_seconds;
    stats.equilibrium = r.equilibrium ? 1 : 0;
    stats.refinement = refinement_stats(r.refinement);
    stats.reduced_offsets = r.reduced_offsets;
    stats.raised_limits = r.raised_limits;
    stats.obstacle_vertices = r.obstacle_vertices;
    stats.obstacle_refinement = refinement_stats(r.obstacle_refinement);
    stats.cg_iterations = r.cg_iterations;
    stats.extrapolated_steps = r.extrapolated_steps;
    stats.strain_correction = strain_correction_stats(r.strain_correction);
    *out = stats;
  });
}

}  // extern "C"
