// Hard cases stay finite: stiff thin metal, huge time steps, sliver triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "common/constants.hpp"
#include "mesh/mesh_generators.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;

namespace {

Scene sheet_scene(const TriangleMesh& mesh, const ShellMaterial& material, double time_step,
                  double duration) {
  Scene scene;
  scene.name = "hard";
  scene.time_step = time_step;
  scene.duration = duration;
  scene.effects.enable(Effect::membrane);
  scene.effects.enable(Effect::bending);
  scene.effects.enable(Effect::gravity);
  scene.bodies.push_back({"sheet", mesh, material, 0.0, 0.0});
  return scene;
}

/// Pins the vertices within `radius` of the given corner.
void pin_near(Scene& scene, const Vec3& corner, double radius) {
  Handle h;
  const Positions& v = scene.bodies[0].mesh.vertices;
  for (int i = 0; i < v.rows(); ++i)
    if ((v.row(i).transpose() - corner).norm() < radius) h.vertices.push_back(i);
  scene.handles.push_back(h);
}

/// Runs every step and checks each one is finite and ends with a reported reason.
void run_and_expect_finite(LevelSimulation& sim) {
  int iterations = 0, converged = 0;
  for (int s = 0; s < sim.scene().num_steps(); ++s) {
    const StepRecord r = sim.step();
    iterations += r.newton.iterations;
    converged += r.newton.stop == NewtonStop::converged;
    ASSERT_TRUE(sim.dofs().allFinite()) << "step " << r.step;
    ASSERT_TRUE(std::isfinite(r.newton.energy)) << "step " << r.step;
    EXPECT_NE(r.newton.stop, NewtonStop::non_finite) << "step " << r.step;
    EXPECT_NE(r.newton.stop, NewtonStop::factorization_failed) << "step " << r.step;
  }
  std::cout << "[ hard case ] " << sim.scene().num_steps() << " steps, " << converged
            << " converged, " << iterations << " Newton iterations" << std::endl;
}

/// Aluminium foil: E = 70 GPa, ν = 0.33, t = 10 µm, ρ = 2700 kg/m³.
ShellMaterial aluminium_foil() {
  ShellMaterial m;
  m.youngs_modulus = 7e10;
  m.poisson_ratio = 0.33;
  m.thickness = 1e-5;
  m.density = 2700;
  return m;
}

double min_angle_degrees(const TriangleMesh& mesh) {
  double smallest = 180.0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = mesh.vertices.row(mesh.faces(f, k));
      const Vec3 b = mesh.vertices.row(mesh.faces(f, (k + 1) % 3));
      const Vec3 c = mesh.vertices.row(mesh.faces(f, (k + 2) % 3));
      smallest = std::min(smallest,
                          std::acos((b - a).normalized().dot((c - a).normalized())) * 180.0 / kPi);
    }
  return smallest;
}

}  // namespace

TEST(HardCases, StiffThinAluminiumPlateUnderGravityStaysFinite) {
  const ShellMaterial aluminium = aluminium_foil();
  Scene scene = sheet_scene(make_grid(0.2, 0.2, 20, 20), aluminium, 0.01, 0.2);
  scene.gravity = Vec3(0, 0, -9.81);  // out of plane: the foil folds down from two corners
  pin_near(scene, Vec3(0, 0.2, 0), 0.011);
  pin_near(scene, Vec3(0.2, 0.2, 0), 0.011);
  LevelSimulation sim(scene);
  run_and_expect_finite(sim);
  EXPECT_LT(sim.positions().col(2).minCoeff(), -1e-2);  // it moved under the load
}

TEST(HardCases, StiffThinAluminiumPlateQuasistaticStaysFinite) {
  const ShellMaterial aluminium = aluminium_foil();
  Scene scene = sheet_scene(make_grid(0.2, 0.2, 16, 16), aluminium, 1.0, 3.0);
  scene.mode = StepMode::quasistatic;
  scene.gravity = Vec3(0, 0, -9.81);  // out of plane: the sheet sags between its clamps
  for (double x : {0.0, 0.2}) pin_near(scene, Vec3(x, 0.1, 0), 0.1001);
  LevelSimulation sim(scene);
  run_and_expect_finite(sim);
  std::cout << "[ aluminium ] quasistatic sag " << -sim.positions().col(2).minCoeff() << " m"
            << std::endl;
  EXPECT_LT(sim.positions().col(2).minCoeff(), -1e-4);  // it sagged
}

TEST(HardCases, AQuasistaticSheetHingedOnOneLineSwingsDownToHang) {
  // A 1 m square sheet held only along its edge x = 0, gravity normal to it: rotating about
  // that line costs no elastic energy (a mechanism; quasistatics has no inertia), so the flat
  // start's Hessian is singular. Statics: it hangs straight down, each vertex at depth x₀ and
  // within a centimetre of the plane x = 0 (stretched by at most ρ g L / E = 1 %), its clamp
  // carrying the weight ρ t g A = 9.81 N. Before the line search retried refused steps shortened,
  // the first Newton step was 1e15 m long, 40 halvings could not bring it back, and the sheet
  // stayed flat after 0 iterations.
  ShellMaterial soft;
  soft.youngs_modulus = 1e6;
  soft.poisson_ratio = 0.3;
  soft.thickness = 1e-3;
  soft.density = 1000;
  Scene scene = sheet_scene(make_grid(1, 1, 8, 8), soft, 1.0, 1.0);
  scene.mode = StepMode::quasistatic;
  scene.gravity = Vec3(0, 0, -9.81);
  scene.solver.tolerance = 1e-6;
  Handle hinge;
  const Positions rest = scene.bodies[0].mesh.vertices;
  for (int i = 0; i < rest.rows(); ++i)
    if (rest(i, 0) < 1e-9) hinge.vertices.push_back(i);
  scene.handles.push_back(hinge);
  LevelSimulation sim(scene);
  const StepRecord r = sim.step();
  EXPECT_EQ(r.newton.stop, NewtonStop::converged);
  EXPECT_GT(r.newton.capped_steps, 0);
  const Positions& x = sim.positions();
  const double stretch = soft.density * 9.81 * 1.0 / soft.youngs_modulus;
  for (int i = 0; i < rest.rows(); ++i) {
    // Poisson contraction below the clamped edge puckers it by millimetres (3 mm measured).
    EXPECT_LT(std::abs(x(i, 0)), 0.01) << "vertex " << i;
    EXPECT_LE(-x(i, 2), rest(i, 0) * (1 + stretch) + 1e-9) << "vertex " << i;
    EXPECT_GE(-x(i, 2), rest(i, 0) - 1e-9) << "vertex " << i;
  }
  ASSERT_EQ(r.reactions.size(), 1u);
  EXPECT_NEAR(r.reactions[0].force.z(), 9.81, 1e-6 * 9.81);
}

TEST(HardCases, HugeTimeStepFreeFallFollowsImplicitEulerExactly) {
  // An unconstrained heavy sheet falling with h = 0.1 s: implicit Euler gives
  // v_n = −g h n, y_n = −g h² n(n+1)/2 for every vertex (no deformation).
  ShellMaterial heavy;
  heavy.density = 8000;
  heavy.thickness = 0.01;
  Scene scene = sheet_scene(make_grid(1, 1, 10, 10), heavy, 0.1, 1.0);
  scene.solver.tolerance = 1e-10;
  LevelSimulation sim(scene);
  run_and_expect_finite(sim);
  const double g = 9.81, h = 0.1, n = 10;
  EXPECT_NEAR(sim.positions().col(1).mean() - 0.5, -g * h * h * n * (n + 1) / 2, 1e-6);
}

TEST(HardCases, HugeTimeStepHeavyPinnedDropStaysFinite) {
  ShellMaterial heavy;
  heavy.density = 8000;
  heavy.thickness = 0.005;
  Scene scene = sheet_scene(make_grid(1, 1, 20, 20), heavy, 0.1, 2.0);
  pin_near(scene, Vec3(0, 1, 0), 0.01);
  LevelSimulation sim(scene);
  run_and_expect_finite(sim);
  EXPECT_LT(sim.positions().col(1).minCoeff(), 0.0);
}

TEST(HardCases, SliverTrianglesStayFinite) {
  TriangleMesh mesh = make_grid(1, 1, 20, 20);
  const double cell = 1.0 / 20;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const int column = static_cast<int>(std::lround(mesh.vertices(i, 0) / cell));
    if (column % 2 == 1) mesh.vertices(i, 0) += 0.99 * cell;  // squeeze every other column
  }
  ASSERT_LT(min_angle_degrees(mesh), 1.0);
  ShellMaterial cloth;
  Scene scene = sheet_scene(mesh, cloth, 0.02, 0.4);
  pin_near(scene, Vec3(0, 1, 0), 0.01);
  pin_near(scene, Vec3(1, 1, 0), 0.01);
  LevelSimulation sim(scene);
  run_and_expect_finite(sim);
}
