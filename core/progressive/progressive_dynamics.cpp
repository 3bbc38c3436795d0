#include "progressive/progressive_dynamics.hpp"

#include <string>

#include "common/error.hpp"
#include "common/timer.hpp"
#include "progressive/consistency_projection.hpp"
#include "progressive/progressive_simulation.hpp"

namespace progsim {
namespace {

Scene dynamic_scene(Scene scene) {
  check_progressive_scene(scene);
  if (scene.mode != StepMode::dynamic)
    fail(Status::invalid_scene, scene.name +
                                    ": progressive dynamics animates dynamic scenes; a quasistatic "
                                    "scene is simulated progressively by PSQ");
  return scene;
}

/// P(x) of DOFs (3|V_coarse|) as DOFs (3|V_fine|).
Vector prolong(const ShellProlongation& p, const Vector& coarse) {
  const Positions fine = p(Positions(as_positions(coarse)));
  return as_dofs(fine);
}

/// U v: a coarse velocity prolonged by the intrinsic part (PD eq. 5's V = ∇P with the offsets
/// frozen, PD §4.6).
Vector prolong_velocity(const ShellProlongation& p, const Vector& coarse_velocity) {
  const Positions fine = p.intrinsic() * as_positions(coarse_velocity);
  return as_dofs(fine);
}

/// x̂ of a finer level's step t → t+1 from the coarser frames t and t+1 and the level's own xᵗ.
Vector predicted(DynamicsPrediction rule, const ShellProlongation& p, double h,
                 const Vector& fine_now, const Vector& coarse_now,
                 const Vector& coarse_velocity_now, const Vector& coarse_next) {
  switch (rule) {
    case DynamicsPrediction::velocity_only:  // PD++ / VPD eq. 2: x_{l+1}^t + h U v_l^t
      return fine_now + h * prolong_velocity(p, coarse_velocity_now);
    case DynamicsPrediction::prolonged_positions:  // PD eq. 5: P(x_l^t) + h U v_l^t
      return prolong(p, coarse_now) + h * prolong_velocity(p, coarse_velocity_now);
    case DynamicsPrediction::per_frame:  // PSQ per frame (PD fn. 2): P(x_l^{t+1})
      return prolong(p, coarse_next);
  }
  return fine_now;
}

}  // namespace

ProgressiveDynamics::ProgressiveDynamics(Scene scene,
                                         std::shared_ptr<const MeshHierarchy> hierarchy,
                                         HierarchyProgress progress, void* user)
    : scene_(dynamic_scene(std::move(scene))), hierarchy_(std::move(hierarchy)) {
  if (!hierarchy_)
    hierarchy_ =
        std::make_shared<const MeshHierarchy>(build_scene_hierarchy(scene_, progress, user));
  operators_ = std::make_unique<const LevelOperators>(hierarchy_);
  restart();
}

ProgressiveDynamics::~ProgressiveDynamics() = default;

std::unique_ptr<LevelSimulation> ProgressiveDynamics::make_level(int level) const {
  SimulationLevel spec{hierarchy_, level, {}};
  if (level < finest())
    spec.to_finest = operators_->to_finest(level, scene_.progressive.prolongation);
  if (level > 0) spec.consistency_weight = scene_.progressive.consistency_weight;
  return std::make_unique<LevelSimulation>(scene_, std::move(spec));
}

void ProgressiveDynamics::restart() {
  auto preview = make_level(0);
  Trajectory frames(0, preview->model().rest.num_vertices());
  frames.append(preview->dofs(), preview->velocities());
  DynamicLevelRecord record = start_record(*preview);
  preview_ = std::move(preview);
  trajectories_.clear();
  trajectories_.push_back(std::move(frames));
  records_.assign(1, std::move(record));
  masses_.assign(1, preview_->model().vertex_masses);
}

void ProgressiveDynamics::check_preview_open(const char* what) const {
  if (level() > 0)
    fail(Status::wrong_call_order,
         std::string(what) + ": level " + std::to_string(level()) +
             " has been refined from this preview; restart() before previewing again");
}

StepRecord ProgressiveDynamics::step_preview() {
  check_preview_open("step_preview");
  StepRecord step = preview_->step();
  trajectories_[0].append(preview_->dofs(), preview_->velocities());
  DynamicLevelRecord& record = records_[0];
  add_dynamic_step(record, step, 0.0, 0.0);
  record.terms = preview_->term_totals();
  return step;
}

DynamicLevelRecord start_record(const LevelSimulation& sim) {
  DynamicLevelRecord record;
  record.vertices = sim.model().rest.num_vertices();
  record.start_center_of_mass = sim.center_of_mass();
  return record;
}

double com_deviation(const Vec3& com, const DynamicLevelRecord& level,
                     const DynamicLevelRecord& reference, int t) {
  const Vec3 reference_moved =
      reference.steps.at(t).motion.center_of_mass - reference.start_center_of_mass;
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

void ProgressiveDynamics::update_scene(Scene scene) {
  check_preview_open("update_scene");
  validate_scene(scene);
  if (scene.mode != StepMode::dynamic)
    fail(Status::invalid_scene, "update_scene: progressive dynamics needs a dynamic scene");
  if (scene.time_step != scene_.time_step)
    fail(Status::invalid_argument,
         "update_scene: the time step cannot change within an animation (restart with a new "
         "ProgressiveDynamics)");
  if (!same_levels(scene.progressive, scene_.progressive))
    fail(Status::invalid_argument,
         "update_scene: the progressive levels define the hierarchy and cannot change");
  preview_->update_scene(scene);
  scene_ = std::move(scene);
}

void ProgressiveDynamics::set_preview_velocities(const Vector& velocities) {
  check_preview_open("set_preview_velocities");
  if (preview_->steps_taken() > 0)
    fail(Status::wrong_call_order,
         "set_preview_velocities: the preview has taken steps; restart() to set its initial "
         "velocities");
  preview_->set_velocities(velocities);
  Trajectory frames(0, trajectories_[0].num_vertices());
  frames.append(preview_->dofs(), preview_->velocities());
  trajectories_[0] = std::move(frames);
}

void ProgressiveDynamics::refine(const RefineProgress& progress) {
  const int coarse = level(), fine = coarse + 1;
  if (coarse >= finest())
    fail(Status::out_of_range,
         "level " + std::to_string(coarse) + " is the finest level; there is nothing to refine");
  const Trajectory& from = trajectories_[coarse];
  const int steps = from.num_frames() - 1;
  if (steps < 1) fail(Status::wrong_call_order, "refine: preview at least one step first");
  const ShellProlongation& p = *operators_->next(coarse);
  const double h = scene_.time_step;
  const DynamicsPrediction rule = scene_.progressive.prediction;
  std::unique_ptr<LevelSimulation> sim = make_level(fine);
  Vector x_now, v_now, x_next, v_next;
  from.read(0, x_now, v_now);
  sim->set_velocities(prolong_velocity(p, v_now));  // v_{l+1}^0 = U v_l^0
  Trajectory frames(fine, sim->model().rest.num_vertices());
  frames.append(sim->dofs(), sim->velocities());
  const ConsistencyProjection projection(p.intrinsic(), sim->model().vertex_masses,
                                         masses_[coarse]);
  DynamicLevelRecord record = start_record(*sim);
  for (int t = 0; t < steps; ++t) {
    from.read(t + 1, x_next, v_next);
    StepTargets targets;
    targets.predicted = predicted(rule, p, h, sim->dofs(), x_now, v_now, x_next);
    if (scene_.progressive.consistency_weight > 0.0) targets.consistency = prolong(p, x_next);
    const StepRecord step = sim->step(targets);  // PD eq. 6
    frames.append(sim->dofs(), sim->velocities());
    const double deviation =
        step.motion ? com_deviation(step.motion->center_of_mass, record, records_[0], t) : 0.0;
    add_dynamic_step(record, step, deviation, projection.distance(sim->dofs(), x_next));
    if (progress && !progress(t + 1, steps))
      fail(Status::cancelled, "refining level " + std::to_string(coarse) + " into level " +
                                  std::to_string(fine) + " was cancelled at step " +
                                  std::to_string(t + 1) + " of " + std::to_string(steps));
    std::swap(x_now, x_next);
    std::swap(v_now, v_next);
  }
  record.terms = sim->term_totals();
  masses_.push_back(sim->model().vertex_masses);
  trajectories_.push_back(std::move(frames));
  records_.push_back(std::move(record));
}

void ProgressiveDynamics::check_level(int level) const {
  if (level < 0 || level > finest())
    fail(Status::out_of_range, "level " + std::to_string(level) + " does not exist (levels 0 to " +
                                   std::to_string(finest()) + ")");
  if (level > this->level())
    fail(Status::out_of_range,
         "level " + std::to_string(level) + " has not been computed yet (refine() up to it first)");
}

int ProgressiveDynamics::num_frames(int level) const {
  check_level(level);
  return trajectories_[level].num_frames();
}

void ProgressiveDynamics::read_frame(int level, int frame, Positions& positions,
                                     Positions& velocities) const {
  check_level(level);
  Vector x, v;
  trajectories_[level].read(frame, x, v);
  positions = as_positions(x);
  velocities = as_positions(v);
}

const DynamicLevelRecord& ProgressiveDynamics::record(int level) const {
  check_level(level);
  return records_[level];
}

}  // namespace progsim
