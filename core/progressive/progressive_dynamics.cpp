#include "progressive/progressive_dynamics.hpp"

#include <string>

#include "common/error.hpp"
#include "common/timer.hpp"
#include "progressive/level_refinement.hpp"
#include "progressive/progressive_simulation.hpp"
#include "progressive/safe_refinement.hpp"

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
/// V = ∇P, PD §4.6); a coarser frame refined vertically by PSQ's safe refinement (§4.4).
LevelTransfer shell_transfer(const ShellProlongation& p, const MeshHierarchy& hierarchy,
                             int coarse) {
  LevelTransfer transfer{
      [&p](const Vector& x) { return Vector(as_dofs(p(Positions(as_positions(x))))); },
      [&p](const Vector& v) { return Vector(as_dofs(Positions(p.intrinsic() * as_positions(v)))); },
      &p.intrinsic(),
      {}};
  transfer.vertical = [&hierarchy, coarse](const Vector& frame, const Vector& target,
                                           const LevelSimulation& finer) {
    if (!finer.contact()) return target;
    const RefinementSurroundings around = refinement_surroundings(*finer.contact(), finer.model());
    return Vector(as_dofs(safe_refinement(hierarchy, coarse, Positions(as_positions(frame)),
                                          Positions(as_positions(target)), around)));
  };
  return transfer;
}

}  // namespace

ProgressiveDynamics::ProgressiveDynamics(Scene scene,
                                         std::shared_ptr<const MeshHierarchy> hierarchy,
                                         HierarchyProgress progress, void* user)
    : scene_(dynamic_scene(std::move(scene))),
      hierarchy_(hierarchy ? std::move(hierarchy)
                           : std::make_shared<const MeshHierarchy>(
                                 build_scene_hierarchy(scene_, progress, user))),
      levels_(hierarchy_->finest()) {
  operators_ = std::make_unique<const LevelOperators>(hierarchy_);
  restart();
}

ProgressiveDynamics::~ProgressiveDynamics() = default;

std::unique_ptr<LevelSimulation> ProgressiveDynamics::make_level(int level,
                                                                 LevelStart start) const {
  SimulationLevel spec{hierarchy_, level, {}};
  if (level < finest())
    spec.to_finest = operators_->to_finest(level, scene_.progressive.prolongation);
  if (level > 0) spec.consistency_weight = scene_.progressive.consistency_weight;
  return std::make_unique<LevelSimulation>(scene_, std::move(spec), std::move(start));
}

std::unique_ptr<LevelSimulation> ProgressiveDynamics::direct_level(int level) const {
  check_level_exists(level, finest());
  return std::make_unique<LevelSimulation>(scene_, SimulationLevel{hierarchy_, level, {}});
}

void ProgressiveDynamics::restart() {
  levels_.restart(make_level(0));
}

StepRecord ProgressiveDynamics::step_preview() {
  return levels_.step_preview();
}

void ProgressiveDynamics::update_scene(Scene scene) {
  levels_.update_preview_scene(scene_, scene, scene);
  scene_ = std::move(scene);
}

void ProgressiveDynamics::set_preview_velocities(const Vector& velocities) {
  levels_.set_preview_velocities(velocities);
}

void ProgressiveDynamics::refine_window(StepWindow window, const RefineProgress& progress) {
  levels_.check_refinable(window);
  const int coarse = level();
  levels_.refine([&](LevelStart start) { return make_level(coarse + 1, std::move(start)); },
                 shell_transfer(*operators_->next(coarse), *hierarchy_, coarse), scene_.progressive,
                 scene_.time_step, window, progress);
}

}  // namespace progsim
