// Only the effects a scene calls for are built: unused effects have no term and no counters.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "mesh/mesh_generators.hpp"
#include "sim/level_simulation.hpp"
#include "support/expect_error.hpp"

using namespace progsim;

namespace {

std::vector<std::string> term_names(LevelSimulation& sim) {
  std::vector<std::string> names;
  for (const TermStats& s : sim.term_totals()) names.push_back(s.name);
  return names;
}

Scene scene_with(std::initializer_list<Effect> effects, StepMode mode) {
  Scene scene;
  scene.mode = mode;
  scene.duration = 2 * scene.time_step;
  for (Effect e : effects) scene.effects.enable(e);
  scene.bodies.push_back({"ball", make_sphere(0.1, 1), {}, 500.0, 0.0});
  return scene;
}

}  // namespace

TEST(Effects, OnlyEnabledEffectsHaveTerms) {
  LevelSimulation membrane_only(scene_with({Effect::membrane}, StepMode::quasistatic));
  EXPECT_EQ(term_names(membrane_only), (std::vector<std::string>{"membrane"}));
  LevelSimulation all(scene_with(
      {Effect::membrane, Effect::bending, Effect::gravity, Effect::pressure}, StepMode::dynamic));
  EXPECT_EQ(term_names(all),
            (std::vector<std::string>{"inertia", "membrane", "bending", "gravity", "pressure"}));
}

TEST(Effects, FrictionWithoutContactIsRefusedNamingBoth) {
  // Friction acts on contacts: asked for alone it would be dropped without a word.
  const Scene scene = scene_with({Effect::membrane, Effect::friction}, StepMode::dynamic);
  test_support::expect_error([&] { LevelSimulation sim(scene); }, Status::invalid_scene,
                             {"'friction'", "'contact'"});
}

TEST(Effects, CountersShowWhereTimeWent) {
  LevelSimulation sim(scene_with({Effect::membrane, Effect::pressure}, StepMode::quasistatic));
  const StepRecord r = sim.step();
  ASSERT_EQ(r.terms.size(), 2u);
  for (const TermStats& t : r.terms) {
    EXPECT_GT(t.value_evaluations, 0) << t.name;
    EXPECT_GE(t.hessian_evaluations, std::max(1, r.newton.iterations)) << t.name;
    EXPECT_GE(t.seconds, 0.0);
  }
}

TEST(Effects, ScriptedHandleFollowsItsRigidMotion) {
  Scene scene = scene_with({Effect::membrane, Effect::bending}, StepMode::quasistatic);
  Handle h;
  h.vertices = {0};
  h.motion.angular_velocity = 1.0;
  h.motion.axis = Vec3::UnitY();
  h.motion.velocity = Vec3(0, 0.1, 0);
  scene.handles.push_back(h);
  const Vec3 rest = scene.bodies[0].mesh.vertices.row(0);
  LevelSimulation sim(scene);
  sim.step();
  sim.step();
  const double t = 2 * scene.time_step;
  const Vec3 expected = Eigen::AngleAxisd(t, Vec3::UnitY()) * rest + Vec3(0, 0.1 * t, 0);
  EXPECT_LT((sim.positions().row(0).transpose() - expected).norm(), 1e-14);
}

TEST(Effects, WindTermAndItsRecordExistOnlyWhenAsked) {
  Scene still = scene_with({Effect::membrane, Effect::gravity}, StepMode::dynamic);
  still.wind.velocity = Vec3(0, 0, 5);  // settings alone build nothing
  LevelSimulation without(still);
  const StepRecord off = without.step();
  EXPECT_EQ(term_names(without), (std::vector<std::string>{"inertia", "membrane", "gravity"}));
  EXPECT_FALSE(off.wind.has_value());
  EXPECT_EQ(to_json_line(off).find("\"wind\""), std::string::npos);

  still.effects.enable(Effect::wind);
  LevelSimulation with(still);
  const StepRecord on = with.step();
  EXPECT_EQ(term_names(with), (std::vector<std::string>{"inertia", "membrane", "gravity", "wind"}));
  const TermStats& wind = on.terms.back();
  EXPECT_EQ(wind.name, "wind");
  EXPECT_GT(wind.value_evaluations, 0);
  EXPECT_GT(wind.gradient_evaluations, 0);
  EXPECT_GT(wind.hessian_evaluations, 0);
  ASSERT_TRUE(on.wind.has_value());
  EXPECT_NE(to_json_line(on).find("\"wind\":{\"force\""), std::string::npos);
}
