// The wind effect in a simulation: a free plate in a steady wind accelerates toward the wind
// speed exactly as implicit Euler of the drag equation says, and steps report the wind.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "mesh/mesh_generators.hpp"
#include "sim/level_simulation.hpp"
#include "support/expect_error.hpp"

using namespace progsim;

namespace {

/// A free 1 m × 1 m plate across a wind along z, gravity off; areal density ρ_s t = 0.2 kg/m².
Scene plate_in_wind(double wind_speed, double time_step) {
  Scene scene;
  scene.time_step = time_step;
  scene.duration = 10.0;
  scene.effects.enable(Effect::membrane);
  scene.effects.enable(Effect::wind);
  scene.wind.velocity = Vec3(0.0, 0.0, wind_speed);
  scene.solver.tolerance = 1e-9;
  ShellMaterial cloth;
  cloth.youngs_modulus = 1e5;
  cloth.thickness = 1e-3;
  cloth.density = 200.0;
  scene.bodies.push_back({"plate", make_grid(1.0, 1.0, 4, 4), cloth, 0.0, 0.0});
  return scene;
}

/// One implicit-Euler step of m v' = ½ρC_dA (w − v')² toward w: the lag d' = w − v' solves
/// (c h / m) d'² + d' − d = 0.
double next_lag(double lag, double drag_per_mass, double h) {
  const double a = drag_per_mass * h;
  return (std::sqrt(1.0 + 4.0 * a * lag) - 1.0) / (2.0 * a);
}

}  // namespace

TEST(Wind, FreePlateAcceleratesToTheWindSpeedAsImplicitEulerPredicts) {
  const double w = 10.0, h = 0.05;
  const Scene scene = plate_in_wind(w, h);
  const double drag_per_mass =
      0.5 * scene.wind.density * scene.wind.drag / (scene.bodies[0].material.density * 1e-3);
  LevelSimulation sim(scene);
  double lag = w;  // at rest: the whole wind is relative
  for (int step = 0; step < 200; ++step) {
    const StepRecord r = sim.step();
    lag = next_lag(lag, drag_per_mass, h);
    ASSERT_TRUE(r.wind.has_value());
    EXPECT_EQ(r.wind->velocity, scene.wind.velocity);
    // The plate translates rigidly: every vertex has the same velocity (lumped mass and drag
    // both a third of each face's area), along the wind only.
    for (int v = 0; v < sim.model().rest.num_vertices(); ++v) {
      const Vec3 velocity = sim.velocities().segment<3>(3 * v);
      ASSERT_NEAR(velocity.z(), w - lag, 1e-6 * w) << "step " << step << " vertex " << v;
      ASSERT_LT(velocity.head<2>().norm(), 1e-9 * w);
    }
  }
  EXPECT_LT(lag, 0.04 * w) << "after 10 s the plate moves at nearly the wind speed";
  EXPECT_GT(lag, 0.0) << "and never faster";
}

TEST(Wind, StepReportsTheGustAtItsEndTimeAndTheForceOnTheShell) {
  Scene scene = plate_in_wind(0.0, 0.1);
  scene.wind.keyframes = {{0.0, Vec3(0.0, 0.0, 0.0)}, {1.0, Vec3(0.0, 0.0, 10.0)}};
  LevelSimulation sim(scene);
  const StepRecord r = sim.step();
  ASSERT_TRUE(r.wind.has_value());
  EXPECT_NEAR(r.wind->velocity.z(), 1.0, 1e-12) << "the wind at t = h = 0.1 s";
  const double u = r.wind->velocity.z() - sim.velocities()[2];  // relative wind after the step
  EXPECT_NEAR(r.wind->force.z(), 0.5 * scene.wind.density * scene.wind.drag * u * u, 1e-6);
}

TEST(Wind, QuasistaticSceneIsRefused) {
  Scene scene = plate_in_wind(5.0, 0.1);
  scene.mode = StepMode::quasistatic;
  scene.handles.push_back({0, {0}, {}});
  test_support::expect_error([&] { LevelSimulation sim(scene); }, Status::invalid_scene,
                             {"'wind' effect needs a dynamic scene"});
}
