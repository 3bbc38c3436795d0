#include "sim/level_simulation.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/timer.hpp"
#include "energy/consistency_penalty.hpp"
#include "energy/dead_loads.hpp"
#include "energy/follower_loads.hpp"
#include "energy/gravity.hpp"
#include "energy/inertia.hpp"
#include "energy/pressure.hpp"
#include "energy/prolonged_elastics.hpp"
#include "energy/wind_force.hpp"
#include "mesh/intersection_check.hpp"
#include "sim/contact_setup.hpp"
#include "sim/handle_reactions.hpp"
#include "sim/handle_step_bound.hpp"
#include "sim/load_forces.hpp"
#include "sim/obstacle_script.hpp"
#include "sim/shell_elastics.hpp"
#include "sim/start_separation.hpp"

namespace progsim {
namespace {

/// Validates first, so that nothing is built from a bad scene.
Scene validated(Scene scene) {
  validate_scene(scene);
  return scene;
}

/// Re-aims of follower loads (each followed by a solve) after a step's first solve; a step
/// whose directions still turn by more than the tolerance after them reports the last count.
constexpr int kMaxFollowerLags = 50;

/// Follower loads' directions have settled when no vertex normal turned by more than this (rad)
/// since the last solve, or by more than the solver's relative tolerance if that is larger: a
/// relative force error far below the discretisation's, and above the turn a converged solve's
/// round-off makes (a 40-cell strip solved to 1e-9 turned its normals by 1e-9 to 1e-8 rad).
constexpr double kFollowerAngleTolerance = 1e-6;

/// Rounds of CCD-safe scripted motion (each followed by a solve) before a step gives up.
constexpr int kMaxScriptRounds = 50;

/// A round of scripted handle motion leaves every face next to a handle at least this fraction
/// of its area (max_handle_step()): a handle moved about an edge length in one step would
/// otherwise land on its free neighbours, collapsing the faces between them (a non-finite
/// membrane energy), before the solve could move them aside.
constexpr double kKeptArea = 0.5;

/// A scripted step shorter than this fraction ends the rounds: the contact bounding it is
/// better resolved by the step's own solve than by many solves that each gain little.
constexpr double kStalledScriptStep = 1e-3;

/// Sums the iterations and timings of a solve into a step's report; the rest is the last solve's.
void accumulate(NewtonReport& total, const NewtonReport& part) {
  NewtonReport sum = part;  // the last solve's stop, energy and norms
  sum.iterations += total.iterations;
  sum.exact_steps += total.exact_steps;
  sum.cg_iterations += total.cg_iterations;
  sum.extrapolated_steps += total.extrapolated_steps;
  sum.capped_steps += total.capped_steps;
  sum.symbolic_analyses += total.symbolic_analyses;
  sum.max_shift = std::max(total.max_shift, part.max_shift);
  sum.timings += total.timings;
  total = sum;
}

}  // namespace

std::size_t LevelSimulation::intersecting_face_pairs() const {
  if (contact_) return crossing_faces(*contact_, x_, 0).size();
  return intersecting_faces(Positions(as_positions(x_)), model_.rest.faces).size();
}

LevelSimulation::LevelSimulation(Scene scene) : LevelSimulation(std::move(scene), {}, {}) {}

LevelSimulation::LevelSimulation(Scene scene, SimulationLevel level, LevelStart start)
    : scene_(validated(std::move(scene))),
      level_(std::move(level)),
      obstacles_(std::make_unique<ObstacleScript>(scene_)),
      steps_taken_(start.steps_taken),
      fit_to_start_(start.fit_to_start),
      start_obstacles_(std::move(start.obstacles)),
      start_stiffness_(start.contact_stiffness) {
  build_models();
  const int n = model_.rest.num_vertices();
  const bool given = start.positions.size() > 0;
  if (given && start.positions.size() != 3 * n)
    fail(Status::invalid_argument, "the start state has " + std::to_string(start.positions.size()) +
                                       " DOFs, level " + std::to_string(level_.level) + " has " +
                                       std::to_string(3 * n));
  x_ = given ? std::move(start.positions) : Vector(as_dofs(model_.rest.vertices));
  v_ = Vector::Zero(x_.size());
  if (scene_.mode == StepMode::dynamic && !given)
    for (std::size_t b = 0; b < scene_.bodies.size(); ++b)
      for (int v = model_.vertex_offset[b]; v < model_.vertex_offset[b + 1]; ++v)
        v_.segment<3>(3 * v) = scene_.bodies[b].velocity;
  length_ = bounding_box_diagonal(model_.rest.vertices);
  build_problem();
}

void LevelSimulation::build_models() {
  ShellModel finest = build_shell_model(scene_);
  const std::vector<int> finest_handles = vertex_handles(scene_, finest);
  if (!level_.hierarchy || level_.is_finest()) {
    if (level_.hierarchy)
      check_hierarchy_matches(*level_.hierarchy, finest.rest, finest_handles,
                              scene_.handles.size());
    handles_ = HandleTargets(scene_, finest.rest.vertices, finest_handles);
    model_ = std::move(finest);
    finest_.reset();
    return;
  }
  const MeshHierarchy& h = *level_.hierarchy;
  check_hierarchy_matches(h, finest.rest, finest_handles, scene_.handles.size());
  model_ = level_shell_model(finest, h, level_.level);
  if (scene_.mode == StepMode::dynamic && !level_.to_finest.empty())  // PD eq. 4's M_l
    model_.vertex_masses = prolonged_masses(level_.to_finest, finest.vertex_masses);
  finest_handles_ = HandleTargets(scene_, finest.rest.vertices, finest_handles);
  handles_ = HandleTargets(scene_, model_.rest.vertices, level_groups(h, level_.level));
  // Both hold what a coarse level's proxy cannot: a group free to translate, a lagged normal.
  const std::string coarse = ": level " + std::to_string(level_.level) + " is a coarse level";
  if (!handles_.carried_dofs().empty())
    fail(Status::unsupported, "a rotation support needs a direct simulation" + coarse);
  if (has_follower_loads(scene_))
    fail(Status::unsupported, "a follower load (normal_force) needs a direct simulation" + coarse);
  finest_ =
      !level_.to_finest.empty() ? std::make_shared<const ShellModel>(std::move(finest)) : nullptr;
}

LevelSimulation::~LevelSimulation() = default;

void LevelSimulation::build_problem() {
  // Built aside and committed at the end: on Error (e.g. an intersecting start) the simulation
  // keeps its previous problem. The previous contact term passes on obstacle positions and κ.
  const int n = model_.rest.num_vertices();
  auto problem = std::make_unique<Problem>(3 * n);
  Inertia* inertia = nullptr;
  RampedTerms ramped;
  const EffectSet& fx = scene_.effects;
  if (scene_.mode == StepMode::dynamic || scene_.progressive.proximal)  // PSQ eq. 1 / 3
    inertia = &problem->add_term(std::make_unique<Inertia>(model_.vertex_masses, scene_.time_step));
  add_elastics(*problem, ramped);
  Inertia* penalty = nullptr;
  if (scene_.mode == StepMode::dynamic && level_.consistency_weight > 0.0)  // VPD eq. 4
    penalty = &problem->add_term(std::make_unique<ConsistencyPenalty>(
        model_.vertex_masses, level_.consistency_weight, scene_.time_step));
  const AirCoefficients air{scene_.wind.density, scene_.wind.drag, scene_.wind.lift};
  WindForce* wind = fx.has(Effect::wind)
                        ? &problem->add_term(std::make_unique<WindForce>(model_.rest.faces, n, air))
                        : nullptr;
  ContactPotential* contact = fx.has(Effect::contact) ? &add_contact(*problem) : nullptr;
  FrictionPotential* friction = nullptr;
  if (contact && fx.has(Effect::friction))
    if (auto term = make_friction_potential(scene_, *contact))
      friction = &problem->add_term(std::move(term));
  StrainLimit* strain_limit = nullptr;
  if (fx.has(Effect::strain_limit))
    if (auto term = make_strain_limit(model_)) {
      if (fit_to_start_) term->fit_limits(x_);
      strain_limit = &problem->add_term(std::move(term));
    }
  problem->set_fixed_dofs(handles_.fixed_dofs(n));
  problem->set_shared_dofs(handles_.shared_dofs());  // rotation supports' free translations
  problem->finalize();
  problem_ = std::move(problem);
  scripted_ = handles_.scripted_dofs(n);
  // A new simulation's groups embody their rest pose, so the first step turns them to the
  // script's (a keyframe's first rotation too); a rebuild keeps the pose unless its carried
  // DOFs changed, when a group holds the pose it has now.
  if (carried_pose_.size() != static_cast<Eigen::Index>(handles_.carried_dofs().size()))
    carried_pose_ = steps_taken_ == 0 ? handles_.carried_rest() : handles_.carried_targets(time());
  inertia_ = inertia;
  penalty_ = penalty;
  ramped_ = std::move(ramped);
  contact_ = contact;
  wind_ = wind;
  friction_ = friction;
  friction_lagged_ = false;
  strain_limit_ = strain_limit;
  proxy_ = dynamic_cast<ProlongedElastics*>(problem_->find_term("prolonged_elastics"));
  pin_finest_handles(time());
}

void LevelSimulation::pin_finest_handles(double t) {
  if (proxy_) proxy_->pin_finest_dofs(finest_handles_.dofs(), finest_handles_.dof_targets(t));
}

std::vector<VertexForces> LevelSimulation::level_loads() const {
  if (scene_.loads.empty()) return {};
  if (finest_) return load_forces(scene_, *finest_);
  if (level_.is_finest()) return load_forces(scene_, model_);
  return restrict_loads(load_forces(scene_, build_shell_model(scene_)), *level_.hierarchy,
                        level_.level);
}

void LevelSimulation::add_elastics(Problem& problem, RampedTerms& ramped) const {
  if (finest_) return add_proxy_elastics(problem, ramped);
  ShellElastics own = make_shell_elastics(scene_, model_, true);  // the level's own energy
  ramped.pressures = own.pressures;
  ramped.gravity = own.gravity;
  for (auto& term : own.terms) problem.add_term(std::move(term));
  if (!scene_.loads.empty())
    ramped.loads =
        &problem.add_term(std::make_unique<DeadLoads>(level_loads(), model_.rest.num_vertices()));
  if (!has_follower_loads(scene_)) return;  // coarse levels refused them (build_models)
  ramped.followers = &problem.add_term(std::make_unique<FollowerLoads>(
      normal_loads(scene_, model_), model_.rest.faces, model_.rest.num_vertices()));
}

void LevelSimulation::add_proxy_elastics(Problem& problem, RampedTerms& ramped) const {
  // A dynamic preview's gravity acts on the prolonged masses M_l its inertia uses: through the
  // prolongation it would also act on the offsets a(x), a torque that makes a free fall deform.
  const bool dynamic = scene_.mode == StepMode::dynamic;
  if (dynamic && scene_.effects.has(Effect::gravity))
    ramped.gravity =
        &problem.add_term(std::make_unique<Gravity>(model_.vertex_masses, scene_.gravity));
  const MembraneModel membrane = scene_.progressive.preview_membrane;
  ShellElastics finest = make_shell_elastics(scene_, *finest_, !dynamic, membrane);  // Ψ_L, eq. 2
  if (!scene_.loads.empty()) {  // point loads act where they are: on finest vertices, at P(x)
    auto loads = std::make_unique<DeadLoads>(level_loads(), finest_->rest.num_vertices());
    ramped.loads = loads.get();
    finest.terms.push_back(std::move(loads));
  }
  if (finest.terms.empty()) return;
  ramped.pressures = finest.pressures;
  if (finest.gravity) ramped.gravity = finest.gravity;
  const ProxyHessian hessian = scene_.progressive.hessian;
  if (hessian == ProxyHessian::galerkin || (hessian == ProxyHessian::automatic && dynamic)) {
    // Lazily only where each step is solved to the tolerance: PSQ's capped preview steps
    // (preview_iterations) took more iterations with it and ended elsewhere.
    // A dynamic scene's hinges take the Gauss–Newton block (make_shell_elastics): here, where
    // the Galerkin matrix only preconditions the proxy, on the 34K drape's 30-step preview 371
    // against 375 Newton iterations in 46.9 s against 91.9 s. PSQ's capped previews keep the
    // exact block: there it moves where the capped steps end.
    const double refresh = dynamic ? scene_.progressive.galerkin_refresh *
                                         mean_edge_length(finest_->topology, finest_->rest.vertices)
                                   : 0.0;
    problem.add_term(std::make_unique<ProlongedElastics>(level_.to_finest, std::move(finest.terms),
                                                         finest_->rest.vertices, refresh));
    return;
  }
  ShellElastics own = make_shell_elastics(scene_, model_, false, membrane);  // preconditioner
  ramped.pressures.insert(ramped.pressures.end(), own.pressures.begin(), own.pressures.end());
  problem.add_term(std::make_unique<ProlongedElastics>(level_.to_finest, std::move(finest.terms),
                                                       std::move(own.terms)));
}

ContactPotential& LevelSimulation::add_contact(Problem& problem) {
  auto contact = make_contact_potential(scene_, model_, *obstacles_);
  const Eigen::Index num_obstacle = contact->obstacle_positions().rows();
  if (contact_ && contact_->obstacle_positions().rows() == num_obstacle)
    contact->set_obstacle_positions(contact_->obstacle_positions());
  else if (start_obstacles_.rows() == num_obstacle && num_obstacle > 0)
    contact->set_obstacle_positions(start_obstacles_);  // where the previous level left them
  else
    contact->set_obstacle_positions(obstacles_->at(time()));
  const double kappa = contact_ ? contact_->stiffness() : start_stiffness_;
  contact->set_stiffness(std::max(contact->stiffness(), kappa));
  if (level_.hierarchy && !level_.is_finest())
    check_crossing_free(*contact, x_,
                        scene_.name + ": the start of level " + std::to_string(level_.level) +
                            " (decimated to " + std::to_string(model_.rest.num_vertices()) +
                            " vertices) intersects",
                        level_.hierarchy->levels[level_.level].input_vertex);
  else
    check_crossing_free(*contact, x_, scene_.name + ": the start intersects");
  if (fit_to_start_) contact->fit_offsets(x_);
  contact->check_separated(x_);
  return problem.add_term(std::move(contact));
}

Positions LevelSimulation::obstacle_positions() const {
  return contact_ ? contact_->obstacle_positions() : Positions(0, 3);
}

void LevelSimulation::apply_ramps(double t) {
  for (auto& [term, b] : ramped_.pressures) {
    const Body& body = scene_.bodies[b];
    term->set_pressure(ramp_factor(t, body.pressure_ramp) * body.pressure);
  }
  if (ramped_.gravity)
    ramped_.gravity->set_acceleration(ramp_factor(t, scene_.gravity_ramp) * scene_.gravity);
  for (std::size_t k = 0; ramped_.loads && k < scene_.loads.size(); ++k)
    ramped_.loads->set_factor(k, ramp_factor(t, scene_.loads[k].ramp));
  for (std::size_t k = 0; ramped_.followers && k < scene_.loads.size(); ++k)
    ramped_.followers->set_factor(k, ramp_factor(t, scene_.loads[k].ramp));
}

double LevelSimulation::advance_scripts(double t, double decrement_scale, NewtonReport& report) {
  script_target_ = x_;
  handles_.apply(t, script_target_);
  carried_step_.setZero(x_.size());
  const Vector carried_change = handles_.carried_targets(t) - carried_pose_;
  for (std::size_t i = 0; i < handles_.carried_dofs().size(); ++i)
    carried_step_[handles_.carried_dofs()[i]] = carried_change[static_cast<Eigen::Index>(i)];
  const double reached = script_rounds(t, decrement_scale, report);
  carried_pose_ += reached * carried_change;  // a turn contact cut short goes on next solve
  return reached;
}

double LevelSimulation::script_rounds(double t, double decrement_scale, NewtonReport& report) {
  const Positions obstacle_target = obstacles_->at(t);  // empty without contact
  double reached = 0.0;
  for (int round = 0; round < kMaxScriptRounds; ++round) {
    script_step_ = script_target_ - x_;             // handles only: the solve moves the free DOFs
    for (int d = 0; d < problem_->num_dofs(); ++d)  // a rotation support: the turn still ahead
      if (!problem_->is_fixed(d)) script_step_[d] = (1.0 - reached) * carried_step_[d];
    const Positions obstacles_now = obstacle_positions();
    if (script_step_.isZero(0.0) && obstacles_now == obstacle_target) return 1.0;
    const double alpha = max_script_step(obstacle_target);
    if (alpha >= 1.0) {
      finish_scripts(t, obstacle_target);
      return 1.0;
    }
    if (!(alpha >= kStalledScriptStep)) break;  // also NaN (a non-finite motion): move nothing
    x_ += alpha * script_step_;
    if (contact_)
      contact_->set_obstacle_positions(obstacles_now + alpha * (obstacle_target - obstacles_now));
    reached += alpha * (1.0 - reached);
    fit_limits_to_prescribed_motion();
    const NewtonReport round_solve =
        solver_.minimize(*problem_, x_, scene_.solver, decrement_scale, length_);
    accumulate(report, round_solve);
    // A solve that did not move (its first step was below the tolerance) left the contact
    // that bounded this round as close as it was: the next rounds would each close its gap
    // tenfold (a Zeno sequence) without pushing back. The step's own solve and the next
    // solve's rounds go on from here. An interrupted solve moves nothing further either.
    if (round_solve.iterations == 0 || round_solve.stop == NewtonStop::interrupted) break;
  }
  return reached;
}

double LevelSimulation::max_script_step(const Positions& obstacle_target) {
  double alpha = 1.0;
  if (contact_) {
    alpha = contact_->max_scripted_step(x_, script_step_, obstacle_target);
    if (alpha < 1.0 && carry_shell(obstacle_target))
      alpha = contact_->max_scripted_step(x_, script_step_, obstacle_target);
  }
  return std::min(alpha, max_handle_step(model_.rest.faces, x_, script_step_, kKeptArea));
}

void LevelSimulation::finish_scripts(double t, const Positions& obstacle_target) {
  x_ += script_step_;  // with the shell vertices the obstacles carry
  if (contact_)
    contact_->set_obstacle_positions(obstacle_target);
  else
    handles_.apply(t, x_);  // exactly at their targets
  fit_limits_to_prescribed_motion();
}

bool LevelSimulation::carry_shell(const Positions& obstacle_target) {
  // Where an obstacle presses on the shell, the free vertices it touches move with it: a
  // stiff shell (a can under a plate) is then pushed along and its solve spreads the motion,
  // instead of each round closing the contact gap tenfold while the shell barely yields.
  const Vector carried = contact_->carried_motion(x_, obstacle_target);
  bool any = false;
  for (int d = 0; d < problem_->num_dofs(); ++d)
    if (!scripted_[d] && carried[d] != 0.0) {
      script_step_[d] = carried[d];
      any = true;
    }
  return any;
}

int LevelSimulation::follow_normals(double decrement_scale, NewtonReport& report) {
  const double settled = std::max(kFollowerAngleTolerance, scene_.solver.tolerance);
  int lags = 0;
  while (lags < kMaxFollowerLags && ramped_.followers->relax(x_, settled) > settled) {
    ++lags;
    const NewtonReport again =
        solver_.minimize(*problem_, x_, scene_.solver, decrement_scale, length_);
    accumulate(report, again);
    if (again.stop != NewtonStop::converged) break;
  }
  return lags;
}

void LevelSimulation::fit_limits_to_prescribed_motion() {
  // Handles moved faces next to them beyond their strain limit, where the barrier is infinite
  // (a twist's first free row lags the turned edge): their limits are raised and the following
  // solves bring them back down (StrainLimit::fit_limits, as for a refined start).
  if (strain_limit_ && strain_limit_->fit_limits(x_, StrainLimit::FitAfter::motion) > 0)
    fit_to_start_ = true;
}

void LevelSimulation::update_scene(Scene scene) {
  validate_scene(scene);
  const bool same_size = scene.bodies.size() == scene_.bodies.size() &&
                         std::equal(scene.bodies.begin(), scene.bodies.end(), scene_.bodies.begin(),
                                    [](const Body& a, const Body& b) {
                                      return a.mesh.num_vertices() == b.mesh.num_vertices() &&
                                             a.mesh.num_faces() == b.mesh.num_faces();
                                    });
  if (!same_size)
    fail(Status::invalid_argument, "update_scene: the bodies' meshes must keep their sizes");
  std::swap(scene_, scene);
  ShellModel model = model_;
  HandleTargets handles = handles_, finest_handles = finest_handles_;
  std::shared_ptr<const ShellModel> finest = finest_;
  auto obstacles = std::make_unique<ObstacleScript>(scene_);
  std::swap(obstacles_, obstacles);
  try {
    build_models();
    build_problem();
  } catch (const Error&) {  // e.g. a thicker shell now overlaps: keep the previous scene
    std::swap(scene_, scene);
    model_ = std::move(model);
    handles_ = std::move(handles);
    finest_handles_ = std::move(finest_handles);
    finest_ = std::move(finest);
    std::swap(obstacles_, obstacles);
    throw;
  }
  if (scene_.mode == StepMode::quasistatic) v_.setZero();
}

StepRecord LevelSimulation::step() {
  return solve_at((steps_taken_ + 1) * scene_.time_step, true);
}

StepRecord LevelSimulation::step(const StepTargets& targets) {
  check_targets(targets);
  return solve_at((steps_taken_ + 1) * scene_.time_step, true, targets);
}

void LevelSimulation::check_targets(const StepTargets& targets) const {
  const auto check = [&](const Vector& target, const char* what) {
    if (target.size() != x_.size())
      fail(Status::invalid_argument, std::string(what) + " has " + std::to_string(target.size()) +
                                         " DOFs, level " + std::to_string(level_.level) + " has " +
                                         std::to_string(x_.size()));
    if (!target.allFinite())
      fail(Status::invalid_argument, std::string(what) + " has a non-finite entry");
  };
  if (targets.predicted.size() > 0) check(targets.predicted, "the predicted state x̂");
  if (targets.start.size() > 0) check(targets.start, "the step's start");
  if (penalty_) check(targets.consistency, "the consistency penalty's target");
}

void LevelSimulation::set_velocities(const Vector& velocities) {
  if (scene_.mode != StepMode::dynamic)
    fail(Status::wrong_call_order, scene_.name + " is quasistatic: it has no velocities to set");
  if (velocities.size() != v_.size())
    fail(Status::invalid_argument, "velocities: " + std::to_string(velocities.size()) +
                                       " values given, the level has " + std::to_string(v_.size()) +
                                       " DOFs");
  if (!velocities.allFinite()) fail(Status::invalid_argument, "velocities: a non-finite entry");
  v_ = velocities;
}

StepRecord LevelSimulation::settle() {
  return solve_at(time(), false);
}

StepRecord LevelSimulation::solve_at(double t, bool new_step, const StepTargets& targets) {
  Timer timer;
  const std::vector<TermStats> before = term_totals();
  const double h = scene_.time_step;
  const bool dynamic = scene_.mode == StepMode::dynamic;
  const Vector older = dynamic ? Vector(x_ - h * v_) : Vector();  // xᵗ⁻¹ (v = (xᵗ − xᵗ⁻¹)/h)
  x_previous_ = x_;
  if (targets.start.size() > 0) start_step_at(targets.start);
  // x̂ = xᵗ + h vᵗ (implicit Euler; v = 0: xᵗ), or the coarser level's prediction (PD eq. 5).
  if (inertia_)
    inertia_->set_target(targets.predicted.size() > 0 ? targets.predicted
                                                      : Vector(x_previous_ + h * v_));
  if (penalty_) penalty_->set_target(targets.consistency);
  if (wind_) wind_->lag(x_, v_, h, scene_.wind.at(t));  // forces at the step's end time
  if (contact_) contact_->reset_min_gap();
  const ContactStats contact_before = contact_ ? contact_->stats() : ContactStats{};
  // Lagged friction (IPC §5): frozen at the step's start, or at the first solve after a rebuild.
  if (friction_ && (new_step || !friction_lagged_)) {
    friction_->lag(x_);
    friction_lagged_ = true;
  }
  apply_ramps(t);
  pin_finest_handles(t);
  if (ramped_.followers) ramped_.followers->aim(x_);
  StepRecord record;
  const double decrement_scale = dynamic ? h : 1.0;
  record.script_reached = advance_scripts(t, decrement_scale, record.newton);
  accumulate(record.newton,
             solver_.minimize(*problem_, x_, scene_.solver, decrement_scale, length_));
  if (ramped_.followers) record.follower_lags = follow_normals(decrement_scale, record.newton);
  if (fit_to_start_) restore_fitted(record);
  record.change_rms = (x_ - x_previous_).norm() / std::sqrt(x_.size() / 3.0);
  record.equilibrium =
      !dynamic && record.script_reached >= 1.0 && record.raised_limits == 0 && at_rest(record);
  if (dynamic || (!handles_.empty() && !proxy_)) problem_->unreduced_gradient(x_, gradient_);
  if (!handles_.empty() && !proxy_)  // a preview's proxy passes no force of a pinned finest DOF
    record.reactions = handle_reactions(handles_, x_, gradient_);
  if (dynamic) {
    v_ = (x_ - x_previous_) / h;  // vᵗ⁺¹ = (xᵗ⁺¹ − xᵗ)/h
    record.motion = motion(older, x_previous_, inertia_->target());
  }
  if (new_step) ++steps_taken_;
  record.step = steps_taken_;
  record.time = t;
  const std::vector<TermStats> after = term_totals();
  for (std::size_t k = 0; k < before.size(); ++k) record.terms.push_back(after[k].since(before[k]));
  if (contact_) record.contact = contact_->stats().since(contact_before);
  if (friction_) record.friction_contacts = friction_->num_contacts();
  if (strain_limit_) record.max_stretch = strain_limit_->max_stretch(x_);
  if (wind_) record.wind = WindRecord{wind_->wind(), wind_->total_force(x_)};
  record.seconds = timer.seconds();
  return record;
}

Vec3 LevelSimulation::center_of_mass() const {
  const Eigen::VectorXd& m = model_.vertex_masses;
  return (m.transpose() * as_positions(x_)).transpose() / m.sum();
}

MotionRecord LevelSimulation::motion(const Vector& older, const Vector& before,
                                     const Vector& predicted) const {
  const Eigen::VectorXd& m = model_.vertex_masses;
  const double h = scene_.time_step;
  MotionRecord out;
  for (Eigen::Index i = 0; i < m.size(); ++i)
    out.kinetic_energy += 0.5 * m[i] * v_.segment<3>(3 * i).squaredNorm();  // ½ vᵀMv
  out.center_of_mass = center_of_mass();
  // VPD App. C eqs. 17–18 (PD++): the midpoint estimate from implicit Euler as a boundary value
  // problem, with h²M⁻¹f(xᵗ⁺¹) = xᵗ⁺¹ − x̂ − h²M⁻¹∇E read from the solve.
  double error = 0.0, residual = 0.0, free_mass = 0.0;
  for (Eigen::Index d = 0; d < x_.size(); ++d) {
    if (scripted_[d]) continue;
    const double md = m[d / 3];
    const double step = h * h * gradient_[d] / md;  // h²M⁻¹∇E
    const double midpoint = 0.5 * (older[d] + predicted[d] + step);
    error += md * (before[d] - midpoint) * (before[d] - midpoint);
    residual += md * 0.25 * step * step;
    free_mass += md;
  }
  if (free_mass == 0.0) return out;
  out.continuity_error = std::sqrt(error / free_mass);
  const double allowed = 0.5 * h * scene_.solver.tolerance * length_;  // Newton's stop, ½ h ε ℓ
  out.continuity = out.continuity_error / std::max(std::sqrt(residual / free_mass), allowed);
  return out;
}

bool LevelSimulation::at_rest(const StepRecord& record) const {
  const NewtonStop stop = record.newton.stop;
  if (!level_.to_finest.empty())  // a preview: PSQ Algorithm 1 line 10, ‖d‖₂ < √n_l h ε
    return (stop == NewtonStop::converged || stop == NewtonStop::max_iterations) &&
           record.change_rms < scene_.solver.tolerance * length_;
  return stop == NewtonStop::converged &&
         (!scene_.progressive.proximal || record.newton.iterations == 0);
}

void LevelSimulation::start_step_at(const Vector& start) {
  x_ = start;
  if (contact_) contact_->fit_offsets(x_);  // as a refined LevelStart (PSQ §4.4.3)
  if (strain_limit_) strain_limit_->fit_limits(x_, StrainLimit::FitAfter::motion);
  fit_to_start_ = true;
}

void LevelSimulation::restore_fitted(StepRecord& record) {
  // Raise the lowered offsets and lower the raised limits as far as the solve allows. A solve
  // leaves no other pair inside its offset, so without lowered offsets there is nothing to
  // refit (and no broad phase to pay for: prescribed motion raises limits every step).
  if (contact_ && contact_->reduced_offsets() > 0)
    record.reduced_offsets = contact_->fit_offsets(x_);
  if (strain_limit_) record.raised_limits = strain_limit_->fit_limits(x_);
  fit_to_start_ = record.reduced_offsets > 0 || record.raised_limits > 0;
}

std::vector<TermStats> LevelSimulation::term_totals() const {
  std::vector<TermStats> totals = problem_->term_stats();
  if (proxy_) {
    const std::vector<TermStats> finest = proxy_->finest_term_stats();
    totals.insert(totals.end(), finest.begin(), finest.end());
  }
  return totals;
}

}  // namespace progsim
