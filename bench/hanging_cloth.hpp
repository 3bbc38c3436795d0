#pragma once
/// @file The benchmarks' contact-free cloth: a square of n×n cells hanging from its two top
/// corners (membrane, bending, gravity), about (n+1)² vertices.
#include "mesh/mesh_generators.hpp"
#include "scene/scene.hpp"

namespace progsim::bench {

inline Scene hanging_cloth(int n) {
  Scene scene;
  scene.name = "bench_cloth";
  scene.time_step = 0.02;
  scene.effects.enable(Effect::membrane);
  scene.effects.enable(Effect::bending);
  scene.effects.enable(Effect::gravity);
  scene.solver.tolerance = 1e-4;
  scene.bodies.push_back({"cloth", make_grid(1.0, 1.0, n, n), {}, 0.0, 0.0});
  Handle corners;
  corners.vertices = {n * (n + 1), (n + 1) * (n + 1) - 1};  // the two corners at y = 1
  scene.handles.push_back(corners);
  return scene;
}

}  // namespace progsim::bench
