// Wind in Progressive Dynamics: every level, the preview through the proxy energy included,
// is blown downwind as implicit Euler of the drag equation predicts for the whole cloth (the
// wind acts on each level's own faces); each level's steps report the wind as direct steps do.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh/mesh_generators.hpp"
#include "progressive/dynamics_report.hpp"
#include "progressive/progressive_dynamics.hpp"
#include "progressive/progressive_test_scenes.hpp"

using namespace progsim;
using namespace progsim::test_support;

TEST(WindProgressive, EveryLevelIsBlownDownwindAlike) {
  const int steps = 10;
  const double w = 10.0;
  Scene scene = falling_cloth(steps, 0.02);
  scene.effects.disable(Effect::gravity);
  scene.effects.enable(Effect::wind);
  scene.wind.velocity = Vec3(0.0, 0.0, w);
  scene.solver.tolerance = 1e-6;
  // The Galerkin Hessian: with the level's own Hessian standing in for the proxy's, the previews
  // of this flexing cloth converged linearly, most steps hitting 100 iterations.
  scene.progressive.hessian = ProxyHessian::galerkin;
  ProgressiveDynamics pd(scene);
  for (int n = 0; n < steps; ++n) pd.step_preview();
  pd.refine();
  pd.refine();
  // The cloth's momentum: M (V' − V)/h = ½ρC_dA (w − V')² with A its area, M its mass.
  const double drag_per_mass = 0.5 * scene.wind.density * scene.wind.drag / (300.0 * 5e-4);
  const double a = drag_per_mass * scene.time_step;
  double lag = w, travelled = 0.0;
  for (int n = 0; n < steps; ++n) {
    lag = (std::sqrt(1.0 + 4.0 * a * lag) - 1.0) / (2.0 * a);
    travelled += scene.time_step * (w - lag);
  }
  for (int level = 0; level <= 2; ++level) {
    const DynamicLevelRecord& record = pd.record(level);
    EXPECT_EQ(record.converged_steps, steps) << "level " << level;
    const Vec3 start = record.steps.front().motion.center_of_mass;
    const double moved = record.steps.back().motion.center_of_mass.z() - start.z();
    // The first record is after step 1: the recursion's first step is behind it.
    const double first = scene.time_step * (w - (std::sqrt(1.0 + 4.0 * a * w) - 1.0) / (2.0 * a));
    // Within 2 %: a coarse level's lumped drag (a third of its own faces' areas) and its
    // prolonged masses differ from vertex to vertex, so it flexes a little as it speeds up.
    EXPECT_NEAR(moved, travelled - first, 0.02 * travelled) << "level " << level;
  }
}

TEST(WindProgressive, EveryLevelsStepsCarryTheWindRecordOnlyWithWind) {
  const int steps = 2;
  Scene still = falling_cloth(steps);
  Scene windy = still;
  windy.effects.disable(Effect::gravity);
  windy.effects.enable(Effect::wind);
  windy.wind.velocity = Vec3(0.0, 0.0, 10.0);
  for (const Scene& scene : {still, windy}) {
    const bool wind = scene.effects.has(Effect::wind);
    ProgressiveDynamics pd(scene);
    for (int n = 0; n < steps; ++n) pd.step_preview();
    pd.refine();
    pd.refine();
    for (int level = 0; level <= 2; ++level) {
      const std::vector<DynamicStepRecord>& records = pd.record(level).steps;
      ASSERT_EQ(records.size(), std::size_t(steps));
      for (const DynamicStepRecord& s : records) {
        SCOPED_TRACE("wind " + std::to_string(wind) + ", level " + std::to_string(level) +
                     ", step " + std::to_string(s.step));
        const nlohmann::json line = dynamic_step_json(level, s);  // its steps.jsonl line
        ASSERT_EQ(s.wind.has_value(), wind);
        ASSERT_EQ(line.contains("wind"), wind);
        if (!wind) continue;
        EXPECT_EQ(s.wind->velocity, scene.wind.velocity);
        EXPECT_GT(s.wind->force.z(), 0.0);  // the drag pushes the cloth downwind
        EXPECT_EQ(line.at("wind").at("velocity"), nlohmann::json({0.0, 0.0, 10.0}));
        StepRecord direct;  // a direct step's line carries the same object
        direct.wind = s.wind;
        EXPECT_EQ(line.at("wind"), nlohmann::json::parse(to_json_line(direct)).at("wind"));
      }
    }
  }
}
