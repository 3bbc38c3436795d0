#pragma once
/// @file The contact benchmarks' scene: a cloth of (n + 1)² vertices (1 m square, E = 1e5 Pa,
/// t = 0.5 mm, ρ = 400 kg/m³) dropped from 5 cm above a 0.25 m sphere, h = 10 ms, μ = 0.3;
/// with `contact` false, the same cloth falling with no sphere and no contact.
#include <Eigen/Geometry>

#include "common/constants.hpp"
#include "mesh/mesh_generators.hpp"
#include "scene/scene.hpp"

namespace progsim::bench {

inline Scene cloth_over_sphere(int n, int steps, bool contact) {
  Scene scene;
  scene.name = "bench_contact";
  scene.time_step = 0.01;
  scene.duration = steps * scene.time_step;
  for (Effect e : {Effect::membrane, Effect::bending, Effect::gravity}) scene.effects.enable(e);
  if (contact) {
    scene.effects.enable(Effect::contact);
    scene.effects.enable(Effect::friction);
  }
  TriangleMesh cloth = make_grid(1.0, 1.0, n, n);
  const Eigen::AngleAxisd flat(-0.5 * kPi, Vec3::UnitX());
  for (Eigen::Index i = 0; i < cloth.vertices.rows(); ++i)
    cloth.vertices.row(i) =
        (flat * cloth.vertices.row(i).transpose() + Vec3(-0.5, 0.3, 0.5)).transpose();
  ShellMaterial m;
  m.youngs_modulus = 1e5;
  m.thickness = 5e-4;
  m.density = 400;
  m.friction = 0.3;
  scene.bodies.push_back({"cloth", cloth, m, 0.0, 0.0});
  scene.solver.tolerance = 1e-4;
  scene.contact.dhat = 1e-3;
  if (contact) {
    Obstacle sphere;
    sphere.name = "sphere";
    sphere.mesh = make_sphere(0.25, 4);
    sphere.friction = 0.3;
    scene.obstacles.push_back(sphere);
  }
  return scene;
}

}  // namespace progsim::bench
