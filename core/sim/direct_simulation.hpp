#pragma once
/// @file Direct (single-level) simulation of a scene: the baseline every progressive method
/// is compared against, and the finest-level solve of the progressive drivers.
#include <memory>
#include <vector>

#include "problem/problem.hpp"
#include "scene/scene.hpp"
#include "sim/handle_targets.hpp"
#include "sim/shell_model.hpp"
#include "sim/step_record.hpp"
#include "solve/newton_solver.hpp"

namespace progsim {

class Inertia;
class Pressure;
class ContactPotential;
class FrictionPotential;
class StrainLimit;
class ObstacleScript;

/// Builds one energy term per enabled effect and advances the scene step by step with
/// projected Newton. Dynamic scenes minimise the implicit-Euler incremental potential;
/// quasistatic scenes minimise the potential energy at each step's loads.
class DirectSimulation {
 public:
  /// Validates the scene (throws Error on bad input) and builds the problem. With contact, a
  /// scene whose shell and obstacles intersect (CGAL exact predicates) or come within their
  /// contact offsets is rejected with Error(intersecting) naming the pair.
  explicit DirectSimulation(Scene scene);
  DirectSimulation(const DirectSimulation&) = delete;
  DirectSimulation& operator=(const DirectSimulation&) = delete;
  ~DirectSimulation();

  /// Advances one step. Never throws for numerical trouble: a failed Newton solve is
  /// reported in the record's stop reason and the state stays finite (the last iterate
  /// the line search accepted).
  StepRecord step();

  /// Replaces the scene between steps (materials, loads, handles, effects, time step,
  /// solver settings) and rebuilds the problem, keeping positions, velocities and time.
  /// The bodies' meshes must keep their sizes. Validates first: on Error nothing changed.
  void update_scene(Scene scene);

  int steps_taken() const { return steps_taken_; }
  double time() const { return steps_taken_ * scene_.time_step; }
  /// Current positions (|V| × 3), metres.
  Eigen::Map<const Positions> positions() const { return as_positions(x_); }
  /// Current DOFs (3|V|).
  const Vector& dofs() const { return x_; }
  /// Current velocities (3|V|), m/s (zero for quasistatic scenes).
  const Vector& velocities() const { return v_; }
  const ShellModel& model() const { return model_; }
  const Scene& scene() const { return scene_; }
  Problem& problem() { return *problem_; }
  /// Bounding-box diagonal of the rest shape (m): the length scale of tolerances.
  double characteristic_length() const { return length_; }
  /// Total counters per term since construction.
  const std::vector<TermStats>& term_totals() const { return problem_->term_stats(); }
  /// The contact term, or nullptr when the scene does not enable contact.
  const ContactPotential* contact() const { return contact_; }
  /// Obstacle vertex positions now (|V_obstacles| × 3); empty without obstacles.
  Positions obstacle_positions() const;

 private:
  void build_problem();
  /// Adds the contact term after checking that the current state does not intersect.
  ContactPotential& add_contact(Problem& problem);
  void apply_pressure(double t);
  /// Moves handles and obstacles toward their scripts at time t, in CCD-safe rounds with a
  /// Newton solve between rounds when contact stops them; returns the fraction reached.
  double advance_scripts(double t, double decrement_scale, NewtonReport& report);

  Scene scene_;
  ShellModel model_;
  HandleTargets handles_;
  std::unique_ptr<Problem> problem_;
  NewtonSolver solver_;
  Inertia* inertia_ = nullptr;                        // owned by problem_, null for quasistatics
  std::vector<std::pair<Pressure*, int>> pressures_;  // (term, body), owned by problem_
  std::unique_ptr<ObstacleScript> obstacles_;
  ContactPotential* contact_ = nullptr;    // owned by problem_, null without contact
  FrictionPotential* friction_ = nullptr;  // owned by problem_, null without friction
  StrainLimit* strain_limit_ = nullptr;    // owned by problem_, null without a limit
  Vector x_, v_, x_previous_, script_target_, script_step_;
  int steps_taken_ = 0;
  double length_ = 1.0;
};

}  // namespace progsim
