// ps_sim_*: a progressive animation's frames, initial velocities, restarts and statistics.
#include "handles.hpp"

namespace progsim::capi {
namespace {

/// Positions or velocities of one frame of a computed level.
enum class FrameData { positions, velocities };

void copy_frame(const ps_sim& sim, int32_t level, int32_t frame, FrameData what, double* out,
                size_t capacity, size_t* count) {
  Positions positions, velocities;
  animation_driver(sim).read_frame(level, frame, positions, velocities);
  const Positions& values = what == FrameData::positions ? positions : velocities;
  copy_out(values.data(), static_cast<size_t>(values.size()), out, capacity, count);
}

/// The ABI's copy of one step's record.
ps_step_stats step_stats(const DynamicStepRecord& r) {
  ps_step_stats stats{};
  stats.step = r.step;
  stats.newton_iterations = r.newton_iterations;
  stats.converged = r.converged ? 1 : 0;
  stats.time = r.time;
  stats.seconds = r.seconds;
  stats.kinetic_energy = r.motion.kinetic_energy;
  for (int k = 0; k < 3; ++k) stats.center_of_mass[k] = r.motion.center_of_mass[k];
  stats.com_deviation = r.com_deviation;
  stats.continuity = r.motion.continuity;
  stats.continuity_error = r.motion.continuity_error;
  stats.consistency = r.consistency;
  return stats;
}

}  // namespace
}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API int32_t ps_sim_num_frames(const ps_sim* sim, int32_t level, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_num_frames", [&] {
    require_idle(sim);
    require(out, "out");
    *out = animation_driver(*sim).num_frames(level);
  });
}

PS_API int32_t ps_sim_get_frame_positions(const ps_sim* sim, int32_t level, int32_t frame,
                                          double* out, size_t capacity, size_t* count) {
  return guarded(error_slot(sim), "ps_sim_get_frame_positions", [&] {
    require_idle(sim);
    copy_frame(*sim, level, frame, FrameData::positions, out, capacity, count);
  });
}

PS_API int32_t ps_sim_get_frame_velocities(const ps_sim* sim, int32_t level, int32_t frame,
                                           double* out, size_t capacity, size_t* count) {
  return guarded(error_slot(sim), "ps_sim_get_frame_velocities", [&] {
    require_idle(sim);
    copy_frame(*sim, level, frame, FrameData::velocities, out, capacity, count);
  });
}

PS_API int32_t ps_sim_set_preview_velocities(ps_sim* sim, const double* velocities, size_t count) {
  return guarded(error_slot(sim), "ps_sim_set_preview_velocities", [&] {
    require_idle(sim);
    ProgressiveAnimation& animation = animation_driver(*sim);
    if (count > 0) require(velocities, "velocities");
    animation.set_preview_velocities(
        Eigen::Map<const Vector>(velocities, static_cast<Eigen::Index>(count)));
  });
}

PS_API int32_t ps_sim_restart(ps_sim* sim) {
  return guarded(error_slot(sim), "ps_sim_restart", [&] {
    require_idle(sim);
    animation_driver(*sim).restart();
  });
}

PS_API int32_t ps_sim_get_step_stats(const ps_sim* sim, int32_t level, ps_step_stats* out,
                                     size_t capacity, size_t* count) {
  return guarded(error_slot(sim), "ps_sim_get_step_stats", [&] {
    require_idle(sim);
    const std::vector<DynamicStepRecord>& steps = animation_driver(*sim).record(level).steps;
    std::vector<ps_step_stats> stats;
    stats.reserve(steps.size());
    for (const DynamicStepRecord& r : steps) stats.push_back(step_stats(r));
    copy_out(stats.data(), stats.size(), out, capacity, count);
  });
}

PS_API int32_t ps_sim_get_dynamic_level_stats(const ps_sim* sim, int32_t level,
                                              ps_dynamic_level_stats* out) {
  return guarded(error_slot(sim), "ps_sim_get_dynamic_level_stats", [&] {
    require_idle(sim);
    require(out, "out");
    const DynamicLevelRecord& r = animation_driver(*sim).record(level);
    ps_dynamic_level_stats stats{};
    stats.level = level;
    stats.vertices = r.vertices;
    stats.steps = static_cast<int32_t>(r.steps.size());
    stats.newton_iterations = r.newton_iterations;
    stats.converged_steps = r.converged_steps;
    stats.first_step = r.first_step;
    stats.seconds = r.seconds;
    *out = stats;
  });
}

}  // extern "C"
