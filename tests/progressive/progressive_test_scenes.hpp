#pragma once
/// @file Small quasistatic scenes shared by the progressive-simulation tests.
#include <cmath>

#include "common/constants.hpp"
#include "mesh/mesh_generators.hpp"
#include "scene/scene.hpp"

namespace progsim::test_support {

/// Rows of a mesh's vertices whose coordinate `axis` is within 1e-9 of `value`.
inline std::vector<int> vertices_at(const TriangleMesh& mesh, int axis, double value) {
  std::vector<int> out;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (std::abs(mesh.vertices(v, axis) - value) < 1e-9) out.push_back(v);
  return out;
}

/// A quasistatic one-body scene with membrane, bending and gravity (−z), one load step.
inline Scene shell_scene(TriangleMesh mesh, const ShellMaterial& material) {
  Scene scene;
  scene.name = "progressive_test";
  scene.mode = StepMode::quasistatic;
  scene.time_step = 1.0;
  scene.duration = 1.0;
  scene.gravity = Vec3(0.0, 0.0, -9.81);
  for (Effect e : {Effect::membrane, Effect::bending, Effect::gravity}) scene.effects.enable(e);
  scene.bodies.push_back({"shell", std::move(mesh), material, 0.0, 0.0});
  return scene;
}

/// A half-pipe (radius 5 cm, 40 cm long, axis y) clamped at y = 0 and sagging under gravity:
/// a curved shell whose coarse meshes lock in membrane (PSQ §1, Fig. 4).
inline Scene curved_cantilever(int n_around, int n_along) {
  ShellMaterial material;
  material.youngs_modulus = 1e9;
  material.poisson_ratio = 0.3;
  material.thickness = 1e-3;
  material.density = 1000.0;
  Scene scene = shell_scene(make_cylinder(0.05, 0.4, kPi, n_around, n_along), material);
  Handle clamp;
  clamp.vertices = vertices_at(scene.bodies[0].mesh, 1, 0.0);
  scene.handles.push_back(clamp);
  return scene;
}

}  // namespace progsim::test_support

namespace progsim::test_support {

/// A 1 m square plate of thin metal (E = 7e10 Pa, t = 0.5 mm) in the x–y plane with an upward
/// imperfection of `bump` m, clamped along x = 0 and x = 1 and pressed inwards by 2% over
/// `steps` quasistatic steps: it buckles out of plane (PSQ Fig. 16).
inline Scene buckling_plate(int n, double bump, int steps) {
  TriangleMesh mesh = make_grid(1.0, 1.0, n, n);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    mesh.vertices(v, 2) =
        bump * std::sin(kPi * mesh.vertices(v, 0)) * std::sin(kPi * mesh.vertices(v, 1));
  ShellMaterial steel;
  steel.youngs_modulus = 7e10;
  steel.poisson_ratio = 0.33;
  steel.thickness = 5e-4;
  steel.density = 2700.0;
  Scene scene = shell_scene(std::move(mesh), steel);
  scene.effects.disable(Effect::gravity);
  scene.time_step = 1.0;
  scene.duration = steps;
  for (double side : {0.0, 1.0}) {
    Handle h;
    h.vertices = vertices_at(scene.bodies[0].mesh, 0, side);
    h.motion.velocity = Vec3((side == 0.0 ? 0.01 : -0.01) / steps, 0.0, 0.0);
    scene.handles.push_back(h);
  }
  return scene;
}

/// A 0.5 m cotton-like square cloth (21 × 21 vertices) in the x–y plane under gravity −z,
/// animated with h (10 ms by default) on three levels (30, 120, 441 vertices); nothing holds it.
inline Scene falling_cloth(int steps, double time_step = 0.01) {
  ShellMaterial cloth;
  cloth.youngs_modulus = 1e5;
  cloth.thickness = 5e-4;
  cloth.density = 300.0;
  Scene scene = shell_scene(make_grid(0.5, 0.5, 20, 20), cloth);
  scene.mode = StepMode::dynamic;
  scene.time_step = time_step;
  scene.duration = steps * scene.time_step;
  scene.progressive.level_vertices = {30, 120};
  return scene;
}

}  // namespace progsim::test_support
