#include "progressive/dynamic_records.hpp"

namespace progsim {

DynamicLevelRecord start_record(const LevelSimulation& sim) {
  DynamicLevelRecord record;
  record.vertices = sim.model().rest.num_vertices();
  record.start_center_of_mass = sim.center_of_mass();
  return record;
}

double com_deviation(const Vec3& com, const DynamicLevelRecord& level,
                     const DynamicLevelRecord& reference, int t, int first) {
  const Vec3 reference_start = first == 0 ? reference.start_center_of_mass
                                          : reference.steps.at(first - 1).motion.center_of_mass;
  const Vec3 reference_moved = reference.steps.at(t).motion.center_of_mass - reference_start;
  return ((com - level.start_center_of_mass) - reference_moved).norm();
}

void add_dynamic_step(DynamicLevelRecord& record, const StepRecord& step, double com_deviation,
                      double consistency) {
  DynamicStepRecord r;
  r.step = step.step;
  r.time = step.time;
  r.newton_iterations = step.newton.iterations;
  r.converged = step.newton.stop == NewtonStop::converged;
  r.seconds = step.seconds;
  if (step.motion) r.motion = *step.motion;
  r.com_deviation = com_deviation;
  r.consistency = consistency;
  r.contact = step.contact;
  r.max_stretch = step.max_stretch;
  r.wind = step.wind;
  r.reactions = step.reactions;
  record.seconds += step.seconds;
  record.newton_iterations += r.newton_iterations;
  record.converged_steps += r.converged;
  record.steps.push_back(std::move(r));
}

}  // namespace progsim
