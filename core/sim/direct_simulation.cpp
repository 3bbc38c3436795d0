#include "sim/direct_simulation.hpp"

#include <algorithm>

#include "common/error.hpp"
#include "common/timer.hpp"
#include "energy/gravity.hpp"
#include "energy/hinge_bending.hpp"
#include "energy/inertia.hpp"
#include "energy/neo_hookean_membrane.hpp"
#include "energy/pressure.hpp"

namespace progsim {
namespace {

/// Validates first, so that nothing is built from a bad scene.
Scene validated(Scene scene) {
  validate_scene(scene);
  return scene;
}

/// Faces of body b, renumbered into the merged model.
Faces body_faces(const ShellModel& model, int b) {
  return model.rest.faces.middleRows(model.face_offset[b],
                                     model.face_offset[b + 1] - model.face_offset[b]);
}

}  // namespace

DirectSimulation::DirectSimulation(Scene scene)
    : scene_(validated(std::move(scene))),
      model_(build_shell_model(scene_)),
      handles_(scene_, model_) {
  x_ = as_dofs(model_.rest.vertices);
  v_ = Vector::Zero(x_.size());
  length_ = bounding_box_diagonal(model_.rest.vertices);
  build_problem();
}

DirectSimulation::~DirectSimulation() = default;

void DirectSimulation::build_problem() {
  const int n = model_.rest.num_vertices();
  problem_ = std::make_unique<Problem>(3 * n);
  const EffectSet& fx = scene_.effects;
  const Positions& rest = model_.rest.vertices;
  if (scene_.mode == StepMode::dynamic)
    inertia_ =
        &problem_->add_term(std::make_unique<Inertia>(model_.vertex_masses, scene_.time_step));
  if (fx.has(Effect::membrane))
    problem_->add_term(
        std::make_unique<NeoHookeanMembrane>(rest, model_.rest.faces, model_.face_materials));
  if (fx.has(Effect::bending))
    problem_->add_term(std::make_unique<HingeBending>(
        rest, model_.rest.faces, model_.topology.hinges, model_.face_materials));
  if (fx.has(Effect::gravity))
    problem_->add_term(std::make_unique<Gravity>(model_.vertex_masses, scene_.gravity));
  if (fx.has(Effect::pressure)) {
    for (int b = 0; b < static_cast<int>(scene_.bodies.size()); ++b) {
      if (scene_.bodies[b].pressure == 0.0) continue;
      auto term = std::make_unique<Pressure>(rest, body_faces(model_, b), 0.0);
      pressures_.emplace_back(&problem_->add_term(std::move(term)), b);
    }
  }
  problem_->set_fixed_dofs(handles_.fixed_dofs(n));
  problem_->finalize();
}

void DirectSimulation::apply_loads(double t) {
  for (auto& [term, b] : pressures_) {
    const Body& body = scene_.bodies[b];
    const double ramp = body.pressure_ramp > 0.0 ? std::min(1.0, t / body.pressure_ramp) : 1.0;
    term->set_pressure(ramp * body.pressure);
  }
  handles_.apply(t, x_);
}

void DirectSimulation::update_scene(Scene scene) {
  validate_scene(scene);
  const bool same_size = scene.bodies.size() == scene_.bodies.size() &&
                         std::equal(scene.bodies.begin(), scene.bodies.end(),
                                    scene_.bodies.begin(), [](const Body& a, const Body& b) {
                                      return a.mesh.num_vertices() == b.mesh.num_vertices() &&
                                             a.mesh.num_faces() == b.mesh.num_faces();
                                    });
  if (!same_size)
    fail(Status::invalid_argument, "update_scene: the bodies' meshes must keep their sizes");
  scene_ = std::move(scene);
  model_ = build_shell_model(scene_);
  handles_ = HandleTargets(scene_, model_);
  inertia_ = nullptr;
  pressures_.clear();
  build_problem();
  solver_.reset();
  if (scene_.mode == StepMode::quasistatic) v_.setZero();
}

StepRecord DirectSimulation::step() {
  Timer timer;
  const std::vector<TermStats> before = problem_->term_stats();
  const double h = scene_.time_step;
  const double t = (steps_taken_ + 1) * h;
  x_previous_ = x_;
  if (inertia_) inertia_->set_target(x_ + h * v_);  // x̂ = xᵗ + h vᵗ (implicit Euler)
  apply_loads(t);
  StepRecord record;
  const double decrement_scale = inertia_ ? h : 1.0;
  record.newton = solver_.minimize(*problem_, x_, scene_.solver, decrement_scale, length_);
  if (inertia_) v_ = (x_ - x_previous_) / h;  // vᵗ⁺¹ = (xᵗ⁺¹ − xᵗ)/h
  ++steps_taken_;
  record.step = steps_taken_;
  record.time = t;
  for (std::size_t k = 0; k < before.size(); ++k)
    record.terms.push_back(problem_->term_stats()[k].since(before[k]));
  record.seconds = timer.seconds();
  return record;
}

}  // namespace progsim
