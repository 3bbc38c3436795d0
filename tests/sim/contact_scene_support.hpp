#pragma once
/// @file Scenes and checks shared by the contact simulation tests: horizontal cloths, obstacles,
/// and the independent intersection check (CGAL exact predicates) after every step.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <string>

#include "common/constants.hpp"
#include "contact/contact_potential.hpp"
#include "mesh/intersection_check.hpp"
#include "mesh/mesh_generators.hpp"
#include "sim/level_simulation.hpp"

namespace progsim::contact_scenes {

/// A square cloth of side `size` with n × n quads, horizontal (normal +y), centred over the
/// y axis at height y.
inline TriangleMesh horizontal_cloth(double size, int n, double y) {
  TriangleMesh mesh = make_grid(size, size, n, n);
  const Eigen::AngleAxisd to_horizontal(-0.5 * kPi, Vec3::UnitX());
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    const Vec3 p = to_horizontal * mesh.vertices.row(i).transpose();
    mesh.vertices.row(i) = (p + Vec3(-0.5 * size, y, 0.5 * size)).transpose();
  }
  return mesh;
}

/// Cotton-like cloth material with friction μ.
inline ShellMaterial cloth_material(double friction) {
  ShellMaterial m;
  m.youngs_modulus = 1e5;
  m.thickness = 5e-4;
  m.density = 400;
  m.friction = friction;
  return m;
}

/// A dynamic scene with one cloth body and the membrane, bending, gravity and contact effects.
inline Scene cloth_scene(const TriangleMesh& cloth, double friction, double time_step, int steps) {
  Scene scene;
  scene.name = "contact_test";
  scene.time_step = time_step;
  scene.duration = steps * time_step;
  for (Effect e : {Effect::membrane, Effect::bending, Effect::gravity, Effect::contact})
    scene.effects.enable(e);
  if (friction > 0.0) scene.effects.enable(Effect::friction);
  scene.bodies.push_back({"cloth", cloth, cloth_material(friction), 0.0, 0.0});
  scene.contact.dhat = 2e-3;
  return scene;
}

inline Obstacle static_obstacle(const std::string& name, TriangleMesh mesh, double friction) {
  Obstacle o;
  o.name = name;
  o.mesh = std::move(mesh);
  o.friction = friction;
  return o;
}

/// Shell and obstacles at the simulation's current state: no two faces intersect, by CGAL's
/// exact predicates (independent of progsim's distance and CCD code).
inline void expect_intersection_free(const LevelSimulation& sim, int step) {
  const ContactPotential& contact = *sim.contact();
  Positions all(contact.mesh().num_vertices(), 3);
  all.topRows(contact.mesh().num_shell_vertices) = sim.positions();
  all.bottomRows(contact.mesh().num_obstacle_vertices) = sim.obstacle_positions();
  const auto pairs = intersecting_faces(all, contact.mesh().faces, 1);
  EXPECT_TRUE(pairs.empty()) << "step " << step << ": faces " << pairs.front().a << " and "
                             << pairs.front().b << " intersect";
}

/// Runs every step, checking after each that the state is finite and intersection-free.
/// @return the records
inline std::vector<StepRecord> run_checked(LevelSimulation& sim) {
  std::vector<StepRecord> records;
  for (int s = 0; s < sim.scene().num_steps(); ++s) {
    records.push_back(sim.step());
    const StepRecord& r = records.back();
    EXPECT_TRUE(sim.dofs().allFinite()) << "step " << r.step;
    EXPECT_NE(r.newton.stop, NewtonStop::non_finite) << "step " << r.step;
    EXPECT_NE(r.newton.stop, NewtonStop::factorization_failed) << "step " << r.step;
    expect_intersection_free(sim, r.step);
    if (::testing::Test::HasFailure()) break;
  }
  return records;
}

/// Largest vertex speed (m/s).
inline double max_speed(const LevelSimulation& sim) {
  return as_positions(sim.velocities()).rowwise().norm().maxCoeff();
}

}  // namespace progsim::contact_scenes
