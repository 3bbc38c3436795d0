#include "progressive/progressive_simulation.hpp"

#include <algorithm>
#include <cassert>
#include <string>

#include "common/error.hpp"
#include "common/timer.hpp"
#include "hierarchy/decimation.hpp"
#include "progressive/scene_level_counts.hpp"
#include "sim/contact_setup.hpp"
#include "sim/handle_targets.hpp"
#include "sim/obstacle_script.hpp"
#include "sim/start_separation.hpp"

namespace progsim {
namespace {

Scene validated(Scene scene) {
  check_progressive_scene(scene);
  return scene;
}

/// Throws Error(unsupported), starting with `what`, for a dynamic scene on several levels: PSQ
/// is quasistatic (a single level runs either mode as a direct simulation).
void check_quasistatic_levels(const Scene& scene, int num_levels, const std::string& what) {
  if (num_levels > 1 && scene.mode == StepMode::dynamic)
    fail(Status::unsupported,
         what +
             ": PSQ is quasistatic; a dynamic scene on several levels is animated from its "
             "initial state by Progressive Dynamics (ProgressiveDynamics, or a simulation "
             "created in dynamic mode)");
}

/// build_scene_hierarchy() of a scene that passed check_progressive_scene().
MeshHierarchy checked_scene_hierarchy(const Scene& scene, HierarchyProgress progress, void* user) {
  const ShellModel model = build_shell_model(scene);
  HierarchyOptions options;
  options.coarse_vertex_counts = scene_coarse_counts(scene.progressive, model.rest.num_vertices());
  options.vertex_groups = vertex_handles(scene, model);
  if (std::any_of(scene.bodies.begin(), scene.bodies.end(), is_solid)) {
    if (mixes_shells_and_solids(scene) && !options.coarse_vertex_counts.empty())
      fail(Status::unsupported, scene.name +
                                    ": the scene mixes shells and volumetric (tet) bodies, which "
                                    "progressive runs do not simulate on several levels yet: "
                                    "simulate it on one level (directly)");
    if (!options.coarse_vertex_counts.empty())
      fail(Status::unsupported,
           scene.name +
               ": volumetric (tet) bodies on several levels are animated by VPD "
               "(VolumetricDynamics, dynamic mode); PSQ refines shells only, and simulates a "
               "solid on one level (no coarse levels) directly");
    // One level, validated as tets by validate_scene: build_hierarchy's surface check would
    // refuse the solid's interior vertices, which no boundary face references.
    return decimate(model.rest, options, progress, user);
  }
  if (scene.effects.has(Effect::contact)) options.contact_offsets = shell_contact_offsets(model);
  return build_hierarchy(model.rest, options, progress, user);
}

}  // namespace

bool same_levels(const ProgressiveSettings& a, const ProgressiveSettings& b) {
  return a.coarse_levels == b.coarse_levels && a.coarsening_ratio == b.coarsening_ratio &&
         a.level_vertices == b.level_vertices;
}

void check_progressive_scene(const Scene& scene) {
  validate_scene(scene);
  if (!scene.contact.crossing_start) check_input_contact_free(scene);
}

MeshHierarchy build_scene_hierarchy(const Scene& scene, HierarchyProgress progress, void* user) {
  check_progressive_scene(scene);
  return checked_scene_hierarchy(scene, progress, user);
}

ProgressiveSimulation::ProgressiveSimulation(Scene scene,
                                             std::shared_ptr<const MeshHierarchy> hierarchy,
                                             HierarchyProgress progress, void* user)
    : scene_(validated(std::move(scene))), hierarchy_(std::move(hierarchy)) {
  if (scene_.contact.crossing_start && scene_.effects.has(Effect::contact))
    input_crossing_pairs_ = static_cast<int>(progsim::input_crossing_pairs(scene_));
  if (!hierarchy_)
    hierarchy_ =
        std::make_shared<const MeshHierarchy>(checked_scene_hierarchy(scene_, progress, user));
  check_quasistatic_levels(scene_, hierarchy_->num_levels(), scene_.name);
  if (hierarchy_->num_levels() > 1) {
    std::vector<int> shell_vertices;
    for (const HierarchyLevel& l : hierarchy_->levels)
      shell_vertices.push_back(l.rest.num_vertices());
    auto obstacles = std::make_unique<const ObstacleHierarchy>(scene_, shell_vertices);
    if (!obstacles->empty()) obstacle_levels_ = std::move(obstacles);
  }
  operators_ = std::make_unique<const LevelOperators>(hierarchy_);
  records_.resize(hierarchy_->num_levels());
  sim_ = make_level(0, {});
}

ProgressiveSimulation::~ProgressiveSimulation() = default;

std::vector<std::shared_ptr<const ShellProlongation>> ProgressiveSimulation::to_finest(
    int level) const {
  return operators_->to_finest(level, scene_.progressive.prolongation);
}

Positions ProgressiveSimulation::prolong_to_finest(int level, const Positions& x) const {
  Positions state = x;
  for (const auto& op : to_finest(level)) state = (*op)(state);
  return state;
}

Scene ProgressiveSimulation::level_scene(int level) const {
  Scene scene = scene_;
  if (level == finest()) return scene;
  // A preview step: a few Newton iterations to the preview tolerance (PSQ §4.5, Algorithm 1).
  const ProgressiveSettings& p = scene.progressive;
  scene.solver.max_iterations = std::min(scene.solver.max_iterations, p.preview_iterations);
  if (p.preview_tolerance > 0.0) scene.solver.tolerance = p.preview_tolerance;
  if (obstacle_levels_) obstacle_levels_->use_level(level, scene);
  return scene;
}

std::unique_ptr<LevelSimulation> ProgressiveSimulation::make_level(int level,
                                                                   LevelStart start) const {
  SimulationLevel spec{hierarchy_, level, {}};
  if (level < finest()) spec.to_finest = to_finest(level);
  return std::make_unique<LevelSimulation>(level_scene(level), std::move(spec), std::move(start));
}

void ProgressiveSimulation::record(const StepRecord& step, bool new_step) {
  LevelRecord& r = records_[level_];
  (new_step ? r.steps : r.settles) += 1;
  r.newton_iterations += step.newton.iterations;
  r.cg_iterations += step.newton.cg_iterations;
  r.extrapolated_steps += step.newton.extrapolated_steps;
  r.converged_solves += step.newton.stop == NewtonStop::converged;
  r.solve_seconds += step.seconds;
  r.energy = step.newton.energy;
  r.gradient_norm = step.newton.gradient_norm;
  r.simulated_time = step.time;
  r.equilibrium = step.equilibrium;
  r.obstacle_vertices = obstacle_vertex_count();
  r.reduced_offsets = step.reduced_offsets;
  r.raised_limits = step.raised_limits;
  r.reactions = step.reactions;
}

StepRecord ProgressiveSimulation::step() {
  StepRecord step = sim_->step();
  record(step, true);
  return step;
}

StepRecord ProgressiveSimulation::settle() {
  StepRecord step = sim_->settle();
  record(step, false);
  return step;
}

bool ProgressiveSimulation::settle_to_equilibrium(int max_solves,
                                                  const std::function<void(int)>& after_solve) {
  if (max_solves < 1)
    fail(Status::invalid_argument, "max_solves = " + std::to_string(max_solves) + " must be >= 1");
  for (int k = 0; k < max_solves; ++k) {
    settle();
    if (!sim_->dofs().allFinite())
      fail(Status::numerical_failure, "settling level " + std::to_string(level_) +
                                          " produced non-finite positions (solve " +
                                          std::to_string(k + 1) + ")");
    if (after_solve) after_solve(k + 1);
    if (records_[level_].equilibrium) return true;
  }
  return false;
}

ShellModel ProgressiveSimulation::level_model(int level) const {
  ShellModel model = build_shell_model(scene_);
  return level < finest() ? level_shell_model(model, *hierarchy_, level) : model;
}

StrainCorrectionStats ProgressiveSimulation::correct_refined_strain(
    const ShellModel& model, Vector& start, const Positions& obstacles) const {
  const int fine = level_ + 1;
  const int n = model.rest.num_vertices();
  const std::vector<bool> handles =
      HandleTargets(scene_, model.rest.vertices, level_groups(*hierarchy_, fine)).fixed_dofs(n);
  const auto contact = [&] {
    std::unique_ptr<ContactPotential> potential;
    if (!sim_->contact()) return potential;
    const Scene scene = level_scene(fine);
    const ObstacleScript script(scene);
    potential = make_contact_potential(scene, model, script);
    // Where the refinement left the obstacles (the level's own script time as the fallback).
    potential->set_obstacle_positions(obstacles.rows() == potential->obstacle_positions().rows()
                                          ? obstacles
                                          : script.at(sim_->time()));
    return potential;
  };
  const double length = bounding_box_diagonal(model.rest.vertices);
  // PSQ §4.4.5: the handles and the coarser level's vertices held, the new ones free.
  std::vector<bool> held = handles;
  const std::vector<int> fine_index = level_vertex_index(*hierarchy_, fine);
  for (int id : hierarchy_->levels[level_].input_vertex) {
    assert(fine_index[id] >= 0 && "a coarser level's vertex is on every finer level");
    for (int d = 0; d < 3; ++d) held[3 * fine_index[id] + d] = true;
  }
  StrainCorrectionStats stats = correct_strain(model, held, contact(), length, start);
  if (stats.over_limit_faces == 0) return stats;
  // Held coarse vertices can make the limits unreachable (a cloth on a sphere: the new vertex
  // between two coarse ones on the surface cannot come nearer the chord between them than the
  // surface allows). Then every vertex but the handles moves.
  const StrainCorrectionStats all = correct_strain(model, handles, contact(), length, start);
  stats.over_limit_faces = all.over_limit_faces;
  stats.newton_iterations += all.newton_iterations;
  stats.stretch_after = all.stretch_after;
  stats.moved_coarse_vertices = all.newton_iterations > 0;
  return stats;
}

void ProgressiveSimulation::refine() {
  if (level_ >= finest())
    fail(Status::out_of_range, "already at the finest level " + std::to_string(finest()) +
                                   "; there is nothing to refine");
  Timer timer;
  const std::string where = "refining level " + std::to_string(level_) + ": ";
  const Positions coarse = sim_->positions();
  const Positions target = next_operator(level_)(coarse);  // P^l_{l+1}(x_l), PSQ eq. 7
  if (!target.allFinite())
    fail(Status::numerical_failure, where + "the prolonged state is not finite");
  // Without contact the level starts at the target; with contact, PSQ §4.4's safe expansion
  // gets as close to it as it can without crossing or entering a contact offset.
  SafeRefinementStats refinement, obstacle_refinement;
  StrainCorrectionStats strain_correction;
  Vector start = as_dofs(target);
  std::unique_ptr<LevelSimulation> next;
  try {
    const ContactPotential* contact = sim_->contact();
    Positions obstacles = sim_->obstacle_positions();
    const ShellModel model = level_model(level_ + 1);
    if (contact) {
      const RefinementSurroundings around = refinement_surroundings(*contact, model);
      start =
          as_dofs(safe_refinement(*hierarchy_, level_, coarse, target, around, {}, &refinement));
      obstacles = refined_obstacles(start, around, &obstacle_refinement);
    }
    if (scene_.effects.has(Effect::strain_limit))
      strain_correction = correct_refined_strain(model, start, obstacles);
    next = make_level(level_ + 1, {std::move(start), sim_->steps_taken(), true,
                                   std::move(obstacles), contact ? contact->stiffness() : 0.0});
  } catch (const Error& e) {
    if (e.status() != Status::intersecting) throw;
    fail(Status::intersecting, where + e.what());
  }
  if (!std::isfinite(next->problem().value(next->dofs())))
    fail(Status::numerical_failure, where + "the refined state has no finite energy");
  records_[level_].positions = coarse;
  sim_ = std::move(next);
  ++level_;
  records_[level_].refine_seconds += timer.seconds();
  records_[level_].refinement = refinement;
  records_[level_].obstacle_refinement = obstacle_refinement;
  records_[level_].strain_correction = strain_correction;
  records_[level_].obstacle_vertices = obstacle_vertex_count();
}

int ProgressiveSimulation::obstacle_vertex_count() const {
  return sim_->contact() ? sim_->contact()->mesh().num_obstacle_vertices : 0;
}

Positions ProgressiveSimulation::refined_obstacles(const Vector& start,
                                                   const RefinementSurroundings& around,
                                                   SafeRefinementStats* stats) const {
  if (!obstacle_levels_) return sim_->obstacle_positions();
  const Positions shell = as_positions(start);
  const Faces& faces = hierarchy_->levels[level_ + 1].rest.faces;
  const double offset =
      around.vertex_offset.empty()
          ? 0.0
          : *std::max_element(around.vertex_offset.begin(), around.vertex_offset.end());
  return obstacle_levels_->refine(level_, sim_->obstacle_positions(), {&shell, &faces, offset},
                                  around.dhat, stats);
}

Positions ProgressiveSimulation::positions(int level) const {
  check_level_exists(level, finest());
  if (level == level_) return sim_->positions();
  if (level < level_) return records_[level].positions;
  Positions x = sim_->positions();
  if (level == finest()) return prolong_to_finest(level_, x);    // the proxy's own map
  for (int k = level_; k < level; ++k) x = next_operator(k)(x);  // PSQ eq. 7 in turn
  return x;
}

std::optional<StateDistance> ProgressiveSimulation::error_against_finest(int level) const {
  check_level_exists(level, finest());
  if (finest() == 0 || level_ != finest() || !records_[finest()].equilibrium) return std::nullopt;
  const Positions converged = sim_->positions();
  if (level == finest()) return StateDistance{};
  const double length = bounding_box_diagonal(hierarchy_->levels.back().rest.vertices);
  return state_distance(prolong_to_finest(level, records_[level].positions), converged, length);
}

void ProgressiveSimulation::update_scene(Scene scene) {
  validate_scene(scene);
  check_quasistatic_levels(scene, hierarchy_->num_levels(), "update_scene");
  if (!same_levels(scene.progressive, scene_.progressive))
    fail(Status::invalid_argument,
         "update_scene: the progressive levels define the hierarchy and cannot change");
  std::swap(scene_, scene);
  try {
    sim_->update_scene(level_scene(level_));
  } catch (const Error&) {
    std::swap(scene_, scene);
    throw;
  }
}

}  // namespace progsim
