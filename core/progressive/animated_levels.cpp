#include "progressive/animated_levels.hpp"

#include <string>

#include "common/error.hpp"
#include "progressive/progressive_simulation.hpp"

namespace progsim {

void AnimatedLevels::restart(std::unique_ptr<LevelSimulation> preview) {
  Trajectory frames(0, preview->model().rest.num_vertices());
  frames.append(preview->dofs(), preview->velocities());
  DynamicLevelRecord record = start_record(*preview);
  preview_ = std::move(preview);
  trajectories_.clear();
  trajectories_.push_back(std::move(frames));
  records_.assign(1, std::move(record));
  masses_.assign(1, preview_->model().vertex_masses);
}

void AnimatedLevels::check_preview_open(const char* what) const {
  if (level() > 0)
    fail(Status::wrong_call_order,
         std::string(what) + ": level " + std::to_string(level()) +
             " has been refined from this preview; restart() before previewing again");
}

void AnimatedLevels::update_preview_scene(const Scene& current, const Scene& updated,
                                          const Scene& preview_scene) {
  check_preview_open("update_scene");
  validate_scene(updated);
  if (updated.mode != StepMode::dynamic)
    fail(Status::invalid_scene, "update_scene: a progressive animation needs a dynamic scene");
  if (updated.time_step != current.time_step)
    fail(Status::invalid_argument,
         "update_scene: the time step cannot change within an animation (restart with a new "
         "driver)");
  if (!same_levels(updated.progressive, current.progressive))
    fail(Status::invalid_argument,
         "update_scene: the progressive levels define the hierarchy and cannot change");
  preview_->update_scene(preview_scene);
}

void AnimatedLevels::set_preview_velocities(const Vector& velocities) {
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

StepRecord AnimatedLevels::step_preview() {
  check_preview_open("step_preview");
  StepRecord step = preview_->step();
  trajectories_[0].append(preview_->dofs(), preview_->velocities());
  DynamicLevelRecord& record = records_[0];
  add_dynamic_step(record, step, 0.0, 0.0);
  record.terms = preview_->term_totals();
  return step;
}

void AnimatedLevels::check_refinable(const StepWindow& window) const {
  if (level() >= finest_)
    fail(Status::out_of_range,
         "level " + std::to_string(level()) + " is the finest level; there is nothing to refine");
  const int steps = trajectories_[level()].num_frames() - 1;
  if (steps != trajectories_[0].num_frames() - 1)  // a window: fewer steps than the preview
    fail(Status::wrong_call_order, "refine: level " + std::to_string(level()) +
                                       " animates a window of the preview's steps only; a finer "
                                       "level needs it over the whole span");
  if (steps < 1) fail(Status::wrong_call_order, "refine: preview at least one step first");
  if (window.first < 0 || window.first >= window.last || window.last > steps)
    fail(Status::invalid_argument, "refine: the window of steps " + std::to_string(window.first) +
                                       " to " + std::to_string(window.last) +
                                       " is not within the previewed steps 0 to " +
                                       std::to_string(steps) + " (first < last)");
}

void AnimatedLevels::refine(const LevelFactory& make, const LevelTransfer& transfer,
                            const ProgressiveSettings& settings, double time_step,
                            StepWindow window, const RefineProgress& progress) {
  check_refinable(window);
  const int coarse = level();
  const CoarserLevel from{&trajectories_[coarse], &masses_[coarse], &records_[0], coarse};
  std::unique_ptr<LevelSimulation> sim = make({});
  if (window.first > 0) sim = make(window_start(*sim, from, transfer, window));
  Trajectory frames(coarse + 1, sim->model().rest.num_vertices());
  DynamicLevelRecord record = start_record(*sim);
  record.first_step = window.first;
  animate_finer_level(*sim, from, transfer, settings, time_step, window, progress, frames, record);
  masses_.push_back(sim->model().vertex_masses);
  trajectories_.push_back(std::move(frames));
  records_.push_back(std::move(record));
}

void AnimatedLevels::check_level(int level) const {
  check_level_exists(level, finest_);
  if (level > this->level())
    fail(Status::out_of_range,
         "level " + std::to_string(level) + " has not been computed yet (refine() up to it first)");
}

int AnimatedLevels::num_frames(int level) const {
  check_level(level);
  return trajectories_[level].num_frames();
}

void AnimatedLevels::read_frame(int level, int frame, Positions& positions,
                                Positions& velocities) const {
  check_level(level);
  Vector x, v;
  trajectories_[level].read(frame, x, v);
  positions = as_positions(x);
  velocities = as_positions(v);
}

const DynamicLevelRecord& AnimatedLevels::record(int level) const {
  check_level(level);
  return records_[level];
}

}  // namespace progsim
