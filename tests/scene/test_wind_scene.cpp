// The scene's "wind" section: defaults from the parameter table, gusts interpolated between
// keyframes and held after the last, and bad input refused naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.hpp"
#include "scene/scene_json.hpp"
#include "support/expect_error.hpp"

using namespace progsim;

namespace {

/// A dynamic sheet with the wind effect and `wind` as its "wind" section (none if empty).
std::string wind_scene(const std::string& wind, const std::string& effects = R"("wind")",
                       const std::string& mode = "dynamic") {
  return R"({ "simulation": {"mode": ")" + mode + R"("}, "effects": ["membrane", )" + effects +
         R"(], "bodies": [ { "mesh": { "generator": "grid", "width": 1, "height": 1, "nx": 2,
         "ny": 2 } } ], "handles": [ { "body": 0, "vertices": [0] } ])" +
         (wind.empty() ? "" : R"(, "wind": )" + wind) + "}";
}

void expect_refused(const std::string& wind, const std::string& needle,
                    const std::string& effects = R"("wind")", const std::string& mode = "dynamic") {
  test_support::expect_error([&] { parse_scene(wind_scene(wind, effects, mode), "."); },
                             Status::invalid_scene, {needle});
}

}  // namespace

TEST(WindScene, DefaultsComeFromTheParameterTable) {
  const Scene scene = parse_scene(wind_scene(R"({"velocity": [3, 0, 1]})"), ".");
  EXPECT_TRUE(scene.effects.has(Effect::wind));
  EXPECT_EQ(scene.wind.velocity, Vec3(3, 0, 1));
  EXPECT_EQ(scene.wind.density, 1.2);
  EXPECT_EQ(scene.wind.drag, 1.2);
  EXPECT_EQ(scene.wind.lift, 0.0);
  EXPECT_EQ(scene.wind.at(7.0), Vec3(3, 0, 1)) << "a steady wind";
  EXPECT_EQ(parse_scene(wind_scene(""), ".").wind.at(1.0), Vec3::Zero()) << "still air";
}

TEST(WindScene, GustsInterpolateLinearlyAndHoldOutsideTheKeyframes) {
  const Scene scene = parse_scene(wind_scene(R"({"density": 1.0, "drag": 2.0, "lift": 0.5,
      "keyframes": [{"time": 1, "velocity": [0, 0, 2]}, {"time": 3, "velocity": [4, 0, 6]},
                    {"time": 4, "velocity": [0, 0, 0]}]})"),
                                  ".");
  const WindSettings& w = scene.wind;
  EXPECT_EQ(w.density, 1.0);
  EXPECT_EQ(w.drag, 2.0);
  EXPECT_EQ(w.lift, 0.5);
  ASSERT_EQ(w.keyframes.size(), 3u);
  EXPECT_EQ(w.at(0.0), Vec3(0, 0, 2)) << "held before the first";
  EXPECT_EQ(w.at(1.0), Vec3(0, 0, 2));
  EXPECT_LT((w.at(1.5) - Vec3(1, 0, 3)).norm(), 1e-15);
  EXPECT_LT((w.at(3.5) - Vec3(2, 0, 3)).norm(), 1e-15);
  EXPECT_EQ(w.at(4.0), Vec3::Zero());
  EXPECT_EQ(w.at(100.0), Vec3::Zero()) << "held after the last";
}

TEST(WindScene, BadInputIsRefusedNamingTheField) {
  expect_refused(R"({"density": -1})", "wind.density = -1");
  expect_refused(R"({"density": 0})", "wind.density = 0");
  expect_refused(R"({"drag": -0.5})", "wind.drag");
  expect_refused(R"({"lift": 1e9})", "wind.lift");
  expect_refused(R"({"velocity": [1, "fast", 0]})", "wind.velocity[1]");
  expect_refused(R"({"velocity": [1, 0]})", "wind.velocity");
  expect_refused(R"({"speed": 3})", "unknown key 'speed'");
  expect_refused(R"({"keyframes": []})", "wind.keyframes");
  expect_refused(R"({"keyframes": [{"time": 1, "velocity": [0, 0, 1]},
                                   {"time": 1, "velocity": [0, 0, 2]}]})",
                 "wind.keyframes[1].time must be later");
  expect_refused(R"({"keyframes": [{"time": -1, "velocity": [0, 0, 1]}]})",
                 "wind.keyframes[0].time");
  expect_refused(R"({"keyframes": [{"velocity": [0, 0, 1]}]})", "missing required field 'time'");
  expect_refused(R"({"velocity": [1, 0, 0], "keyframes": [{"time": 0, "velocity": [0, 0, 1]}]})",
                 "not both");
  expect_refused(R"({"velocity": [1, 0, 0]})", "does not enable the 'wind' effect", R"("gravity")");
  expect_refused("", "needs a dynamic scene", R"("wind")", "quasistatic");
}

TEST(WindScene, CodeBuiltScenesAreValidatedToo) {
  Scene scene = parse_scene(wind_scene(""), ".");
  scene.wind.keyframes = {{2.0, Vec3::Zero()}, {1.0, Vec3::Zero()}};
  test_support::expect_error([&] { validate_scene(scene); }, Status::invalid_scene,
                             {"wind.keyframes[1].time"});
  scene.wind.keyframes.clear();
  scene.wind.velocity.x() = std::nan("");
  test_support::expect_error([&] { validate_scene(scene); }, Status::invalid_scene,
                             {"wind.velocity"});
}
