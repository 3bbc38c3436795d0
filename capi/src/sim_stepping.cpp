// ps_sim_*: preview steps, refinement and reading results per level.
#include <limits>

#include "handles.hpp"
#include "mesh/mesh_io.hpp"

namespace progsim::capi {
namespace {

/// Adds one step's outcome to the level's record.
void record_step(LevelRecord& record, const StepRecord& step, double time) {
  ++record.steps;
  record.newton_iterations += step.newton.iterations;
  record.converged_steps += step.newton.stop == NewtonStop::converged;
  record.seconds += step.seconds;
  record.energy = step.newton.energy;
  record.gradient_norm = step.newton.gradient_norm;
  record.simulated_time = time;
}

/// Positions of a level: the live state for the current level, the kept state for a level
/// already left. (Finer levels appear with the hierarchy's prolongation.)
Positions level_positions(const ps_sim& sim, int32_t level) {
  level_mesh(*sim.hierarchy, level);  // range check
  if (level == sim.level) return sim.simulation->positions();
  return sim.records[level].positions;
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
      const StepRecord step = sim->simulation->step();
      record_step(sim->records[sim->level], step, sim->simulation->time());
      if (!sim->simulation->dofs().allFinite())
        api_fail(PS_ERROR_NUMERICAL,
                 "step " + std::to_string(step.step) + " produced non-finite positions");
      if (sim->progress && sim->progress(sim->progress_user_data, s + 1, steps, "preview") != 0)
        api_fail(PS_ERROR_CANCELLED, "cancelled by the progress callback after " +
                                         std::to_string(s + 1) + " of " + std::to_string(steps) +
                                         " steps");
    }
  });
}

PS_API int32_t ps_sim_refine(ps_sim* sim) {
  return guarded(error_slot(sim), "ps_sim_refine", [&] {
    require_idle(sim);
    const auto finest = sim->hierarchy->mesh_hierarchy.finest();
    // Simulations of multi-level hierarchies are refused at creation (PS_ERROR_UNSUPPORTED)
    // until progressive stepping arrives, so every simulation is at its finest level.
    if (sim->level >= finest)
      api_fail(PS_ERROR_OUT_OF_RANGE, "already at the finest level " + std::to_string(finest) +
                                          "; there is nothing to refine");
  });
}

PS_API int32_t ps_sim_current_level(const ps_sim* sim, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_current_level", [&] {
    require_idle(sim);
    require(out, "out");
    *out = sim->level;
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
    level_mesh(*sim->hierarchy, level);  // range check
    const LevelRecord& r = sim->records[level];
    ps_level_stats stats{};
    stats.level = level;
    stats.steps = r.steps;
    stats.newton_iterations = r.newton_iterations;
    stats.converged_steps = r.converged_steps;
    stats.seconds = r.seconds;
    stats.energy = r.energy;
    stats.gradient_norm = r.gradient_norm;
    stats.simulated_time = r.simulated_time;
    stats.error_rms = stats.error_max = std::numeric_limits<double>::quiet_NaN();
    *out = stats;
  });
}

}  // extern "C"
