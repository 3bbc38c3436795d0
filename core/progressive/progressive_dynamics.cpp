#include "progressive/progressive_dynamics.hpp"

#include <string>

#include "common/error.hpp"
#include "common/timer.hpp"
#include "progressive/level_refinement.hpp"
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

/// The shell prolongation as a level transfer: P(x), and U v with the offsets frozen (PD eq. 5's
/// V = ∇P, PD §4.6).
LevelTransfer shell_transfer(const ShellProlongation& p) {
  return {
      [&p](const Vector& x) { return Vector(as_dofs(p(Positions(as_positions(x))))); },
      [&p](const Vector& v) { return Vector(as_dofs(Positions(p.intrinsic() * as_positions(v)))); },
      &p.intrinsic()};
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
  if (trajectories_[coarse].num_frames() < 2)
    fail(Status::wrong_call_order, "refine: preview at least one step first");
  std::unique_ptr<LevelSimulation> sim = make_level(fine);
  Trajectory frames(fine, sim->model().rest.num_vertices());
  DynamicLevelRecord record = start_record(*sim);
  const CoarserLevel from{&trajectories_[coarse], &masses_[coarse], &records_[0], coarse};
  animate_finer_level(*sim, from, shell_transfer(*operators_->next(coarse)), scene_.progressive,
                      scene_.time_step, progress, frames, record);
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
