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

/// Builds one energy term per enabled effect and advances the scene step by step with
/// projected Newton. Dynamic scenes minimise the implicit-Euler incremental potential;
/// quasistatic scenes minimise the potential energy at each step's loads.
class DirectSimulation {
 public:
  /// Validates the scene (throws Error on bad input) and builds the problem.
  explicit DirectSimulation(Scene scene);
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

 private:
  void build_problem();
  void apply_loads(double t);

  Scene scene_;
  ShellModel model_;
  HandleTargets handles_;
  std::unique_ptr<Problem> problem_;
  NewtonSolver solver_;
  Inertia* inertia_ = nullptr;                        // owned by problem_, null for quasistatics
  std::vector<std::pair<Pressure*, int>> pressures_;  // (term, body), owned by problem_
  Vector x_, v_, x_previous_;
  int steps_taken_ = 0;
  double length_ = 1.0;
};

}  // namespace progsim
