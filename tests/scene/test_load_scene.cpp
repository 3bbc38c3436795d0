// Point and line loads and the gravity ramp in scenes: JSON equals code step by step, bad loads
// are refused naming the load, ramps scale the loads in time.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "energy/dead_loads.hpp"
#include "energy/gravity.hpp"
#include "mesh/mesh_generators.hpp"
#include "scene/scene_json.hpp"
#include "scene/scene_parameters.hpp"
#include "sim/level_simulation.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
namespace pt = progsim::test_support;

namespace {

/// A 0.4 m × 0.1 m strip of 8 × 2 quads clamped on its first two columns, x ≤ 0.05 (one column
/// would be a hinge about which it turns freely), a tip force on x = 0.4 (vertices 8, 17, 26),
/// its weight and a couple on the last two columns ramped over two steps: a few mm each.
const char* const kLoadedStrip = R"({
  "name": "loaded_strip",
  "simulation": { "mode": "quasistatic", "time_step": 0.01, "duration": 0.03 },
  "effects": ["membrane", "bending", "gravity"],
  "gravity": [0, 0, -9.81],
  "bodies": [ { "name": "strip",
                "mesh": { "generator": "grid", "width": 0.4, "height": 0.1, "nx": 8, "ny": 2 },
                "material": { "youngs_modulus": 1e9, "thickness": 0.002 } } ],
  "handles": [ { "body": "strip", "box": { "min": [-1, -1, -1], "max": [0.051, 1, 1] } } ],
  "loads": [
    { "body": "strip", "vertices": [8, 17, 26], "force": [0, 0, -0.02], "distribution": "area" },
    { "body": 0, "box": { "min": [0.34, -1, -1], "max": [1, 1, 1] },
      "moment": { "axis": [0, 1, 0], "magnitude": 0.001 }, "distribution": "per_vertex",
      "ramp": 0.02 } ]
})";

/// kLoadedStrip built in code.
Scene loaded_strip_in_code() {
  Scene scene;
  scene.name = "loaded_strip";
  scene.mode = StepMode::quasistatic;
  scene.time_step = 0.01;
  scene.duration = 0.03;
  scene.effects.enable(Effect::membrane);
  scene.effects.enable(Effect::bending);
  scene.effects.enable(Effect::gravity);
  scene.gravity = Vec3(0, 0, -9.81);
  ShellMaterial material;
  material.youngs_modulus = 1e9;
  material.thickness = 0.002;
  scene.bodies.push_back({"strip", make_grid(0.4, 0.1, 8, 2), material, 0.0, 0.0});
  Handle clamp;
  clamp.vertices = {0, 1, 9, 10, 18, 19};
  scene.handles.push_back(clamp);
  Load tip;
  tip.vertices = {8, 17, 26};
  tip.force = Vec3(0, 0, -0.02);
  tip.distribution = LoadDistribution::area;
  Load couple;
  couple.vertices = {7, 8, 16, 17, 25, 26};
  couple.moment_axis = Vec3::UnitY();
  couple.moment = 0.001;
  couple.distribution = LoadDistribution::per_vertex;
  couple.ramp = 0.02;
  scene.loads = {tip, couple};
  return scene;
}

/// The scene's loads term (nullptr without loads).
const DeadLoads* loads_term(LevelSimulation& sim) {
  return dynamic_cast<const DeadLoads*>(sim.problem().find_term("loads"));
}

}  // namespace

TEST(LoadScene, JsonEqualsTheSceneBuiltInCodeStepByStep) {
  const Scene parsed = parse_scene(kLoadedStrip, ".");
  ASSERT_EQ(parsed.loads.size(), 2u);
  EXPECT_EQ(parsed.loads[1].vertices, (std::vector<int>{7, 8, 16, 17, 25, 26}));
  LevelSimulation from_json(parsed);
  LevelSimulation from_code(loaded_strip_in_code());
  for (int step = 0; step < 3; ++step) {
    const StepRecord a = from_json.step();
    const StepRecord b = from_code.step();
    EXPECT_EQ(a.newton.stop, NewtonStop::converged) << "step " << step;
    EXPECT_EQ(a.newton.iterations, b.newton.iterations) << "step " << step;
    EXPECT_TRUE(from_json.dofs() == from_code.dofs()) << "step " << step;  // bit for bit
  }
  EXPECT_LT(from_json.positions()(26, 2), -1e-4) << "the tip force pulls the tip down";
}

TEST(LoadScene, RampsScaleLoadsAndGravityAtHalfTheirTime) {
  Scene scene = loaded_strip_in_code();
  scene.loads[0].ramp = 0.02;  // t = 0.01 after one step: half of each ramp
  scene.gravity_ramp = 0.02;
  LevelSimulation sim(scene);
  sim.step();
  const DeadLoads* loads = loads_term(sim);
  ASSERT_NE(loads, nullptr);
  EXPECT_NEAR(loads->total_force().z(), 0.5 * -0.02, 1e-16);  // the couple sums to zero
  const auto* gravity = dynamic_cast<const Gravity*>(sim.problem().find_term("gravity"));
  ASSERT_NE(gravity, nullptr);
  EXPECT_EQ(gravity->acceleration(), Vec3(0, 0, -0.5 * 9.81));
  sim.step();
  sim.step();  // past the ramps: full loads
  EXPECT_NEAR(loads_term(sim)->total_force().z(), -0.02, 1e-16);
  EXPECT_EQ(dynamic_cast<const Gravity*>(sim.problem().find_term("gravity"))->acceleration(),
            Vec3(0, 0, -9.81));
}

TEST(LoadScene, GravityRampIsATableParameter) {
  Scene scene = loaded_strip_in_code();
  set_scene_parameter(scene, "simulation.gravity_ramp", 0.5);
  EXPECT_EQ(scene.gravity_ramp, 0.5);
  EXPECT_EQ(scene_parameter(scene, "simulation.gravity_ramp"), 0.5);
  pt::expect_error([&] { set_scene_parameter(scene, "simulation.gravity_ramp", -1.0); },
                   Status::invalid_argument, {"gravity_ramp"});
  std::string text = kLoadedStrip;
  text.replace(text.find("\"duration\": 0.03"), 16, "\"duration\": 0.03, \"gravity_ramp\": 0.2");
  EXPECT_EQ(parse_scene(text, ".").gravity_ramp, 0.2);
  EXPECT_EQ(ramp_factor(0.05, 0.2), 0.25);
  EXPECT_EQ(ramp_factor(0.5, 0.2), 1.0);
  EXPECT_EQ(ramp_factor(0.0, 0.0), 1.0);
}

TEST(LoadScene, BadLoadsAreRefusedNamingTheLoad) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto refused = [](auto change, std::initializer_list<std::string> parts) {
    Scene scene = loaded_strip_in_code();
    change(scene.loads[1]);
    pt::expect_error([&] { validate_scene(scene); }, Status::invalid_scene, parts);
  };
  refused([&](Load& l) { l.force.y() = nan; }, {"loads[1].force has a non-finite value"});
  refused([&](Load& l) { l.moment = INFINITY; }, {"loads[1].moment has a non-finite value"});
  refused([](Load& l) { l.vertices.push_back(27); }, {"loads[1]: vertex 27", "[0, 27)"});
  refused([](Load& l) { l.vertices.push_back(-1); }, {"loads[1]: vertex -1"});
  refused([](Load& l) { l.vertices.clear(); }, {"loads[1]", "selects no vertices"});
  refused([](Load& l) { l.moment_axis.setZero(); }, {"loads[1].moment.axis must be non-zero"});
  refused([](Load& l) { l.ramp = -0.1; }, {"loads[1].ramp"});
  refused([](Load& l) { l.body = 1; }, {"loads[1]: body index 1 does not exist"});
  refused(
      [](Load& l) {
        l.vertices = {8, 17, 26};
        l.moment_axis = Vec3::UnitY();
      },
      {"loads[1].moment", "one line"});  // the tip edge cannot twist about itself
  // Through LevelSimulation: refused before anything is built.
  Scene scene = loaded_strip_in_code();
  scene.loads[0].force.x() = nan;
  pt::expect_error([&] { LevelSimulation sim(scene); }, Status::invalid_scene, {"loads[0].force"});
}

TEST(LoadScene, MalformedJsonLoadsAreRefused) {
  const auto refused = [](const std::string& from, const std::string& to,
                          std::initializer_list<std::string> parts) {
    std::string text = kLoadedStrip;
    text.replace(text.find(from), from.size(), to);
    pt::expect_error([&] { parse_scene(text, "."); }, Status::invalid_scene, parts);
  };
  refused(R"("distribution": "area")", R"("distribution": "volume")",
          {"loads[0].distribution", "volume", "per_vertex"});
  refused(R"("force": [0, 0, -0.02], )", "",
          {"loads[0]", "'force', a 'moment', a 'normal_force' or several"});
  refused(R"("force": [0, 0, -0.02])", R"("force": [0, "a", 0])", {"loads[0].force[1]"});
  refused(R"("magnitude": 0.001)", R"("size": 0.001)", {"loads[1].moment", "size"});
  refused(R"("min": [0.34, -1, -1])", R"("min": [2, -1, -1])", {"loads[1]", "selects no"});
  refused(R"("vertices": [8, 17, 26])", R"("vertices": [8, 17, 99])", {"loads[0]: vertex 99"});
  refused(R"("ramp": 0.02)", R"("ramp": -1)", {"loads[1].ramp"});
  refused(R"("body": "strip", "vertices")", R"("body": "rod", "vertices")", {"loads[0].body"});
}

TEST(LoadScene, AFreeBodyUnderALoadIsRefusedInQuasistaticScenes) {
  Scene scene = loaded_strip_in_code();
  scene.handles.clear();
  scene.effects.disable(Effect::gravity);
  pt::expect_error([&] { validate_scene(scene); }, Status::invalid_scene,
                   {"strip", "loads[0] pulls it"});
}
