#pragma once
/// @file One level's simulation: the scene's bodies on one level of a mesh hierarchy (or on
/// the scene's own mesh) with its problem, its x̂, its scripted handles and obstacles and its
/// step records. The direct baseline is one LevelSimulation with the level's own energy; the
/// progressive drivers (PSQ, PD) compose one per level.
#include <functional>
#include <memory>
#include <vector>

#include "energy/dead_loads.hpp"
#include "problem/problem.hpp"
#include "scene/scene.hpp"
#include "sim/handle_targets.hpp"
#include "sim/shell_model.hpp"
#include "sim/simulation_level.hpp"
#include "sim/step_record.hpp"
#include "solve/newton_solver.hpp"

namespace progsim {

class FollowerLoads;
class Gravity;
class Inertia;
class Pressure;
class ContactPotential;
class FrictionPotential;
class StrainLimit;
class WindForce;
class ObstacleScript;
class ProlongedElastics;

/// Where a level's simulation starts when it continues another level's (PSQ refinement).
struct LevelStart {
  Vector positions;     ///< 3|V_l| DOFs; empty: the level's rest shape
  int steps_taken = 0;  ///< load steps already taken (the scene time)
  /// The start may have pairs within their contact offsets (not crossing) and faces beyond
  /// their strain limits: a refined level (PSQ §4.4). Both are fitted to it and restored by the
  /// solves (ContactPotential::fit_offsets, StrainLimit::fit_limits).
  bool fit_to_start = false;
  Positions obstacles;             ///< where the obstacles are; empty: their script at the time
  double contact_stiffness = 0.0;  ///< κ reached so far (kept if larger than the scene's)
};

/// What a level of a progressive animation steps toward (Progressive Dynamics, PD eqs. 5–6).
struct StepTargets {
  Vector predicted;    ///< x̂ (3|V_l|); empty: xᵗ + h vᵗ, implicit Euler on the level alone
  Vector consistency;  ///< y of the consistency penalty (3|V_l|); required iff the level has one
  /// Where the solve starts (3|V_l|) instead of xᵗ: PSQ per frame's vertical refinement of the
  /// coarser frame (PD §4.3 fn. 3). Crossing-free; pairs within their offsets and faces beyond
  /// their strain limits are fitted to it (as a refined LevelStart). Empty: xᵗ. The velocity
  /// stays (xᵗ⁺¹ − xᵗ)/h.
  Vector start;
};

/// Builds one energy term per enabled effect and advances the scene step by step with
/// projected Newton. Dynamic scenes minimise the implicit-Euler incremental potential;
/// quasistatic scenes minimise the potential energy at each step's loads.
class LevelSimulation {
 public:
  /// Validates the scene (throws Error on bad input) and builds the problem. With contact, a
  /// scene whose shell and obstacles intersect (CGAL exact predicates) or come within their
  /// contact offsets is rejected with Error(intersecting) naming the pair.
  explicit LevelSimulation(Scene scene);
  /// The scene solved at one level of a hierarchy built from its merged bodies (with the
  /// scene's handles as vertex groups), from `start` (the level's rest shape by default). With
  /// `level.to_finest` set the shell energy is the proxy Ψ_L(P^l(x)) of progressive preview
  /// (PSQ eq. 2); otherwise the level's own.
  /// A dynamic scene on a coarse level with the proxy (a Progressive Dynamics preview, PD eq. 4)
  /// takes its inertia and gravity with prolonged_masses(), so that a free fall accelerates
  /// every vertex at g and the prolonged state does not deform. Throws Error(invalid_argument)
  /// if the hierarchy does not match the scene or the start has the wrong size,
  /// Error(intersecting) as above.
  LevelSimulation(Scene scene, SimulationLevel level, LevelStart start = {});
  LevelSimulation(const LevelSimulation&) = delete;
  LevelSimulation& operator=(const LevelSimulation&) = delete;
  ~LevelSimulation();

  /// Advances one step. Never throws for numerical trouble: a failed Newton solve is
  /// reported in the record's stop reason and the state stays finite (the last iterate
  /// the line search accepted).
  StepRecord step();
  /// Advances one step toward `targets` (PD eq. 6): x̂ and the consistency penalty's target
  /// from the coarser level's trajectory. Throws Error(invalid_argument) on a target of the
  /// wrong size or with a non-finite entry, or without the penalty's target on a level that has
  /// the penalty (nothing changed); numerical trouble as step().
  StepRecord step(const StepTargets& targets);

  /// Solves again at the current time with the same loads (no time advance, friction not
  /// re-lagged): reaches equilibrium after a refinement or a parameter change.
  StepRecord settle();

  /// Makes every later Newton solve check `interrupted` before each iteration and stop when it
  /// returns true, mid-step (NewtonStop::interrupted in the record, not at rest): a caller's
  /// time limit. The state stays the last accepted iterate, intersection-free.
  void set_interrupt(std::function<bool()> interrupted) {
    solver_.set_interrupt(std::move(interrupted));
  }

  /// Replaces the scene between steps (materials, loads, handles, effects, time step,
  /// solver settings) and rebuilds the problem, keeping positions, velocities and time.
  /// The bodies' meshes must keep their sizes. Validates first: on Error nothing changed.
  void update_scene(Scene scene);

  /// Sets the velocities (3|V|, m/s) the next step starts from (dynamic scenes). Throws
  /// Error(invalid_argument) on a wrong size or a non-finite entry, Error(wrong_call_order) for a
  /// quasistatic scene (nothing changed).
  void set_velocities(const Vector& velocities);

  int steps_taken() const { return steps_taken_; }
  double time() const { return steps_taken_ * scene_.time_step; }
  /// Current positions (|V| × 3), metres.
  Eigen::Map<const Positions> positions() const { return as_positions(x_); }
  /// Current DOFs (3|V|).
  const Vector& dofs() const { return x_; }
  /// Σ m x / Σ m over the level's vertices now (m), with the level's masses.
  Vec3 center_of_mass() const;
  /// Current velocities (3|V|), m/s (zero for quasistatic scenes).
  const Vector& velocities() const { return v_; }
  const ShellModel& model() const { return model_; }
  const SimulationLevel& level() const { return level_; }
  const Scene& scene() const { return scene_; }
  Problem& problem() { return *problem_; }
  /// Bounding-box diagonal of the rest shape (m): the length scale of tolerances.
  double characteristic_length() const { return length_; }
  /// Total counters per term since construction.
  /// With the proxy energy, the finest-level terms evaluated through it follow, named
  /// "<term>@finest".
  std::vector<TermStats> term_totals() const;
  /// The contact term, or nullptr when the scene does not enable contact.
  const ContactPotential* contact() const { return contact_; }
  /// Face pairs of the shell and the obstacles that cross now, by CGAL's exact predicates (0
  /// is what contact guarantees); without contact, the shell's own crossing face pairs.
  std::size_t intersecting_face_pairs() const;
  /// Obstacle vertex positions now (|V_obstacles| × 3); empty without obstacles.
  Positions obstacle_positions() const;

 private:
  /// model_, handles_ (and finest_ for the proxy) from scene_ and level_.
  void build_models();
  void build_problem();
  /// The terms whose loads ramp up over time (Body::pressure_ramp, Load::ramp,
  /// Scene::gravity_ramp), owned by the problem (or its proxy term).
  struct RampedTerms {
    std::vector<std::pair<Pressure*, int>> pressures;  ///< (term, body)
    Gravity* gravity = nullptr;                        ///< null without gravity
    DeadLoads* loads = nullptr;                        ///< null without loads
    FollowerLoads* followers = nullptr;                ///< null without a normal force
  };
  /// Membrane, bending, gravity, pressure and loads: direct, or through the prolongation.
  void add_elastics(Problem& problem, RampedTerms& ramped) const;
  /// The scene's loads on this level's vertices (load_forces), or, with the proxy energy, on the
  /// finest level's; a direct solve on a coarse level takes them restricted (restrict_loads).
  std::vector<VertexForces> level_loads() const;
  /// One solve at time t (a new step when advancing, the same loads otherwise) toward
  /// `targets` (empty: implicit Euler on the level alone).
  StepRecord solve_at(double t, bool new_step, const StepTargets& targets = {});
  /// Follower loads: re-aims them at x_ and solves again until their directions hold still
  /// (FollowerLoads' fixed point); returns the re-aims after the first solve.
  int follow_normals(double decrement_scale, NewtonReport& report);
  /// Membrane, bending, pressure and loads through the prolongation; gravity through it too for
  /// a quasistatic preview, on the level's prolonged masses for a dynamic one.
  void add_proxy_elastics(Problem& problem, RampedTerms& ramped) const;
  /// The motion after a dynamic step from `before` (xᵗ) and `older` (xᵗ⁻¹), `predicted` its x̂,
  /// with gradient_ the objective's gradient at the new state.
  MotionRecord motion(const Vector& older, const Vector& before, const Vector& predicted) const;
  /// Throws Error(invalid_argument) unless `targets` fit this level.
  void check_targets(const StepTargets& targets) const;
  /// Holds the finest level's handle vertices at their targets at time t in the proxy.
  void pin_finest_handles(double t);
  /// Adds the contact term after checking that the current state does not intersect.
  ContactPotential& add_contact(Problem& problem);
  /// Scales pressures, gravity and loads to their ramps at time t.
  void apply_ramps(double t);
  /// Moves the state to a step's given start and fits the contact offsets and strain limits to it.
  void start_step_at(const Vector& start);
  /// After a solve from a fitted start: offsets and strain limits moved back toward their own
  /// values, what is still fitted counted in `record`.
  void restore_fitted(StepRecord& record);
  /// Moves handles and obstacles toward their scripts at time t, in rounds with a Newton solve
  /// between them when contact (CCD) or a face next to a handle (max_handle_step()) stops
  /// them; returns the fraction reached.
  double advance_scripts(double t, double decrement_scale, NewtonReport& report);
  /// advance_scripts()' rounds toward script_target_ and carried_step_.
  double script_rounds(double t, double decrement_scale, NewtonReport& report);
  /// The fraction of script_step_ (and of the obstacles' way to `obstacle_target`) the next
  /// round may take; with contact may add carried shell motion to script_step_.
  double max_script_step(const Positions& obstacle_target);
  /// Completes the scripted motion: handles at their targets at time t, obstacles at theirs.
  void finish_scripts(double t, const Positions& obstacle_target);
  /// Adds to script_step_ the motion of the free shell vertices that moving obstacles touch
  /// (ContactPotential::carried_motion); returns whether any vertex is carried.
  bool carry_shell(const Positions& obstacle_target);
  /// Raises the strain limits of faces a prescribed motion stretched beyond them.
  void fit_limits_to_prescribed_motion();
  /// Whether the solve behind `record` left the state at rest (StepRecord::equilibrium).
  bool at_rest(const StepRecord& record) const;

  Scene scene_;
  SimulationLevel level_;
  ShellModel model_;
  std::shared_ptr<const ShellModel> finest_;  // the finest model, for the proxy energy only
  HandleTargets handles_;
  std::unique_ptr<Problem> problem_;
  NewtonSolver solver_;
  Inertia* inertia_ = nullptr;  // owned by problem_, null for quasistatics
  RampedTerms ramped_;          // owned by problem_
  std::unique_ptr<ObstacleScript> obstacles_;
  ContactPotential* contact_ = nullptr;    // owned by problem_, null without contact
  FrictionPotential* friction_ = nullptr;  // owned by problem_, null without friction
  StrainLimit* strain_limit_ = nullptr;    // owned by problem_, null without a limit
  WindForce* wind_ = nullptr;              // owned by problem_, null without wind
  ProlongedElastics* proxy_ = nullptr;     // owned by problem_, null for direct solves
  Inertia* penalty_ = nullptr;             // owned by problem_, null without consistency penalty
  HandleTargets finest_handles_;           // the finest level's handles, held exactly by proxy_
  Vector x_, v_, x_previous_, script_target_, script_step_, gradient_;
  Vector carried_step_;  // a step's script change at rotation supports' carried DOFs (3|V|)
  // The script pose the carried DOFs embody (order of HandleTargets::carried_dofs()): the rest
  // pose at first, advanced by the part of each step's change the rounds reached.
  Vector carried_pose_;
  std::vector<bool> scripted_;  // DOFs the scripts move (prescribed or carried)
  int steps_taken_ = 0;
  double length_ = 1.0;
  bool fit_to_start_ = false;  // offsets or strain limits fitted to a start or to prescribed motion
  Positions start_obstacles_;  // LevelStart::obstacles, for the first contact term
  double start_stiffness_ = 0.0;  // LevelStart::contact_stiffness
  bool friction_lagged_ = false;  // friction_ has contacts frozen (else the next solve lags)
};

}  // namespace progsim
