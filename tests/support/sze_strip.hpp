#pragma once
// Sze, Liu & Lo (2004)'s cantilever strip as a quasistatic scene, shared by the bending,
// rotation-support and follower-load tests.
#include <string>
#include <vector>

#include "mesh/mesh_generators.hpp"
#include "scene/scene.hpp"

namespace progsim::test_support {

/// The strip: L = 10, b = 1, h = 0.1, E = 1.2e6, ν = 0, so E I = 100.
inline constexpr double kSzeLength = 10.0, kSzeWidth = 1.0, kSzeThickness = 0.1,
                        kSzeModulus = 1.2e6;
inline constexpr double kSzeBendingStiffness =
    kSzeModulus * kSzeWidth * kSzeThickness * kSzeThickness * kSzeThickness / 12.0;

/// A quasistatic scene (membrane and bending, solved to 1e-9 in at most 500 iterations, steps
/// of `time_step` up to t = 1) of the strip along x from x = `start` to `end` with nx cells along
/// and nx/10 across, ν = 0 and `model` bending; no handles or loads yet.
inline Scene sze_strip_scene(const std::string& name, double start, double end, int nx,
                             BendingModel model, double time_step) {
  Body body;
  body.name = "strip";
  body.mesh = make_grid(end - start, kSzeWidth, nx, nx / 10);
  body.mesh.vertices.col(0).array() += start;
  body.material.youngs_modulus = kSzeModulus;
  body.material.poisson_ratio = 0.0;
  body.material.thickness = kSzeThickness;
  body.material.density = 1.0;
  body.material.bending_model = model;
  Scene scene;
  scene.name = name;
  scene.mode = StepMode::quasistatic;
  scene.time_step = time_step;
  scene.duration = 1.0;
  scene.effects.enable(Effect::membrane);
  scene.effects.enable(Effect::bending);
  scene.solver.tolerance = 1e-9;
  scene.solver.max_iterations = 500;
  scene.bodies.push_back(body);
  return scene;
}

/// The strip's vertices with x < x_max (from below) or x > x_min (from above).
inline std::vector<int> sze_vertices_below(const Scene& scene, double x_max) {
  std::vector<int> out;
  const Positions& p = scene.bodies[0].mesh.vertices;
  for (int v = 0; v < p.rows(); ++v)
    if (p(v, 0) < x_max) out.push_back(v);
  return out;
}
inline std::vector<int> sze_vertices_above(const Scene& scene, double x_min) {
  std::vector<int> out;
  const Positions& p = scene.bodies[0].mesh.vertices;
  for (int v = 0; v < p.rows(); ++v)
    if (p(v, 0) > x_min) out.push_back(v);
  return out;
}

}  // namespace progsim::test_support
