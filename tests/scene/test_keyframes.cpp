// Keyframed motion: each key's pose at its time, held outside the keys, hold / linear / smooth
// between them (smooth with zero velocity at the keys), rotations about one axis over several
// turns and about different axes by slerp; the JSON "motion" keys and bad keys refused by name.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "scene/keyframes.hpp"
#include "scene/scene.hpp"
#include "scene/scene_json.hpp"
#include "support/expect_error.hpp"

using namespace progsim;

namespace {

/// Keys at 0, 1 and 3 s: rest, then translated, then translated and turned a quarter about y.
HandleMotion three_keys(Interpolation mode) {
  HandleMotion m;
  m.center = Vec3(0.5, 0.0, 0.0);
  m.interpolation = mode;
  m.keyframes = {{0.0, Vec3::Zero(), Vec3::UnitZ(), 0.0},
                 {1.0, Vec3(0.2, 0.1, 0.0), Vec3::UnitZ(), 0.0},
                 {3.0, Vec3(0.2, 0.1, -0.4), Vec3::UnitY(), 0.5 * kPi}};
  return m;
}

/// The pose of key k applied to `rest` by hand: c + R(axis, angle)(x̄ − c) + T.
Vec3 hand_pose(const HandleMotion& m, int k, const Vec3& rest) {
  const MotionKeyframe& key = m.keyframes[k];
  const Eigen::AngleAxisd rotation(key.angle, key.axis.normalized());
  return m.center + rotation * (rest - m.center) + key.translation;
}

/// A quasistatic sheet whose handle 0 has `motion` as its JSON "motion".
std::string motion_scene(const std::string& motion) {
  return R"({ "simulation": {"mode": "quasistatic"}, "effects": ["membrane"],
    "bodies": [ { "mesh": { "generator": "grid", "width": 1, "height": 1, "nx": 2, "ny": 2 } } ],
    "handles": [ { "body": 0, "vertices": [0], "motion": )" +
         motion + "} ] }";
}

void expect_motion_refused(const std::string& motion, std::initializer_list<std::string> parts) {
  test_support::expect_error([&] { parse_scene(motion_scene(motion), "."); }, Status::invalid_scene,
                             parts);
}

}  // namespace

TEST(Keyframes, InterpolationWeightsAreStepLineAndSmoothstep) {
  for (double s : {0.0, 0.25, 0.5, 0.9}) {
    EXPECT_EQ(interpolation_weight(Interpolation::hold, s), 0.0);
    EXPECT_EQ(interpolation_weight(Interpolation::linear, s), s);
    EXPECT_NEAR(interpolation_weight(Interpolation::smooth, s), 3 * s * s - 2 * s * s * s, 1e-15);
  }
}

TEST(Keyframes, EachKeysPoseIsReachedAtItsTimeAndHeldOutside) {
  const Vec3 rest(0.1, 0.3, 0.2);
  for (Interpolation mode : {Interpolation::hold, Interpolation::linear, Interpolation::smooth}) {
    const HandleMotion m = three_keys(mode);
    for (int k = 0; k < 3; ++k)
      EXPECT_LT((m.position(rest, m.keyframes[k].time) - hand_pose(m, k, rest)).norm(), 1e-15)
          << "key " << k;
    EXPECT_EQ(m.position(rest, -2.0), m.position(rest, 0.0)) << "held before the first key";
    EXPECT_EQ(m.position(rest, 9.0), m.position(rest, 3.0)) << "held after the last key";
  }
  // hold: the earlier key's pose up to the next key's time
  const HandleMotion hold = three_keys(Interpolation::hold);
  EXPECT_LT((hold.position(rest, 0.999) - rest).norm(), 1e-15);
  EXPECT_LT((hold.position(rest, 2.5) - hand_pose(hold, 1, rest)).norm(), 1e-15);
  // linear: a quarter of the way in time is a quarter of the translation
  const HandleMotion linear = three_keys(Interpolation::linear);
  EXPECT_LT((linear.position(rest, 0.25) - (rest + Vec3(0.05, 0.025, 0.0))).norm(), 1e-15);
}

TEST(Keyframes, SmoothMotionHasZeroVelocityAtTheKeys) {
  // Central differences of the position: O(ε) at each key (smoothstep's slope is 0 there), and
  // 1.5 times the linear rate mid-segment (its slope at s = ½).
  const Vec3 rest(0.1, 0.3, 0.2);
  const HandleMotion smooth = three_keys(Interpolation::smooth);
  const HandleMotion linear = three_keys(Interpolation::linear);
  const double eps = 1e-6;
  const auto velocity = [&](const HandleMotion& m, double t) {
    return Vec3((m.position(rest, t + eps) - m.position(rest, t - eps)) / (2 * eps));
  };
  EXPECT_LT(velocity(smooth, 1.0).norm(), 1e-5) << "at key 1";
  EXPECT_GT(velocity(linear, 1.0 - 2 * eps).norm(), 0.2) << "linear moves into key 1";
  const Vec3 mid = velocity(smooth, 0.5), rate = velocity(linear, 0.5);
  EXPECT_LT((mid - 1.5 * rate).norm(), 1e-6 * rate.norm());
}

TEST(Keyframes, OneAxisTurnsSeveralTimesOtherAxesSlerp) {
  const Vec3 x = Vec3::UnitX();
  HandleMotion spin;
  spin.keyframes = {{0.0, Vec3::Zero(), Vec3::UnitZ(), 0.0},
                    {1.0, Vec3::Zero(), Vec3(0, 0, 2), 4.0 * kPi}};  // two turns, axis not unit
  // a quarter of the time: half a turn (a slerp of the equal end rotations would not move)
  EXPECT_LT((spin.position(x, 0.25) + x).norm(), 1e-14);
  EXPECT_LT((spin.position(x, 0.125) - Vec3::UnitY()).norm(), 1e-14);
  spin.keyframes[1].axis = Vec3(0, 0, -1);  // the opposite axis turns the other way
  EXPECT_LT((spin.position(x, 0.125) + Vec3::UnitY()).norm(), 1e-14);

  // Different axes: the rotation from key a to the pose at w is w times the way to key b
  // (the angle of Rₐᵀ R(w) is w times that of Rₐᵀ R_b, about the same axis).
  HandleMotion tilt;
  tilt.keyframes = {{0.0, Vec3::Zero(), Vec3::UnitX(), 0.5 * kPi},
                    {1.0, Vec3::Zero(), Vec3::UnitY(), 0.5 * kPi}};
  const RigidPose half = keyframe_pose(tilt.keyframes, Interpolation::linear, 0.3);
  const Eigen::AngleAxisd a(0.5 * kPi, Vec3::UnitX()), b(0.5 * kPi, Vec3::UnitY());
  const Eigen::AngleAxisd whole(a.toRotationMatrix().transpose() * b.toRotationMatrix());
  const Eigen::AngleAxisd part(a.toRotationMatrix().transpose() * half.rotation.toRotationMatrix());
  EXPECT_NEAR(part.angle(), 0.3 * whole.angle(), 1e-12);
  EXPECT_LT((part.axis() - whole.axis()).norm(), 1e-12);
}

TEST(Keyframes, WindGustsStillInterpolateLinearly) {
  WindSettings wind;
  wind.keyframes = {{1.0, Vec3(2, 0, 0)}, {3.0, Vec3(6, 0, 4)}};
  EXPECT_EQ(wind.at(0.0), Vec3(2, 0, 0));
  EXPECT_EQ(wind.at(1.5), Vec3(3, 0, 1));
  EXPECT_EQ(wind.at(5.0), Vec3(6, 0, 4));
}

TEST(Keyframes, JsonMotionReadsKeysInterpolationAndCenter) {
  const Scene scene = parse_scene(motion_scene(R"({"center": [0, 1, 0], "interpolation": "smooth",
      "keyframes": [{"time": 0}, {"time": 0.5, "translation": [1, 2, 3], "axis": [0, 2, 0],
                     "angle": 0.25}]})"),
                                  ".");
  const HandleMotion& m = scene.handles[0].motion;
  EXPECT_EQ(m.interpolation, Interpolation::smooth);
  EXPECT_EQ(m.center, Vec3(0, 1, 0));
  ASSERT_EQ(m.keyframes.size(), 2u);
  EXPECT_EQ(m.keyframes[0].translation, Vec3::Zero());
  EXPECT_EQ(m.keyframes[0].axis, Vec3::UnitZ());
  EXPECT_EQ(m.keyframes[1].time, 0.5);
  EXPECT_EQ(m.keyframes[1].translation, Vec3(1, 2, 3));
  EXPECT_EQ(m.keyframes[1].axis, Vec3(0, 2, 0));
  EXPECT_EQ(m.keyframes[1].angle, 0.25);
  EXPECT_TRUE(m.moves());
  EXPECT_EQ(parse_scene(motion_scene(R"({"keyframes": [{"time": 0}]})"), ".")
                .handles[0]
                .motion.interpolation,
            Interpolation::linear);
}

TEST(Keyframes, BadKeysAreRefusedNamingTheKey) {
  const std::string two = R"({"time": 0}, {"time": 1})";
  expect_motion_refused(
      R"({"keyframes": [)" + two + R"(, {"time": 0.5}]})",
      {"handles[0].motion.keyframes[2].time", "later than the keyframe before it"});
  expect_motion_refused(R"({"keyframes": [)" + two + R"(, {"time": 1}]})",
                        {"handles[0].motion.keyframes[2].time"});
  expect_motion_refused(R"({"keyframes": [{"time": 0, "axis": [0, 0, 0]}]})",
                        {"handles[0].motion.keyframes[0].axis", "non-zero"});
  expect_motion_refused(R"({"keyframes": [{"translation": [1, 0, 0]}]})",
                        {"keyframes[0]", "missing required field 'time'"});
  expect_motion_refused(R"({"keyframes": [], "center": [0, 0, 0]})", {"keyframes", "non-empty"});
  expect_motion_refused(R"({"keyframes": [{"time": 0}], "velocity": [1, 0, 0]})",
                        {"handles[0].motion", "'keyframes' or 'velocity'"});
  expect_motion_refused(R"({"keyframes": [{"time": 0}], "angular_velocity": 1})",
                        {"'keyframes' or 'angular_velocity'"});
  expect_motion_refused(R"({"interpolation": "smooth"})", {"interpolation", "needs 'keyframes'"});
  expect_motion_refused(R"({"keyframes": [{"time": 0}], "interpolation": "cubic"})",
                        {"interpolation", "unknown 'cubic'", "hold"});
  expect_motion_refused(R"({"keyframes": [{"time": 0, "angle": "x"}]})", {"keyframes[0].angle"});
}

TEST(Keyframes, CodeBuiltMotionsAreValidatedToo) {
  Scene scene = parse_scene(motion_scene(R"({"keyframes": [{"time": 0}, {"time": 1}]})"), ".");
  const auto refused = [&](auto edit, std::initializer_list<std::string> parts) {
    Scene bad = scene;
    edit(bad.handles[0].motion);
    test_support::expect_error([&] { validate_scene(bad); }, Status::invalid_scene, parts);
  };
  const double nan = std::nan("");
  refused([&](HandleMotion& m) { m.keyframes[1].time = nan; },
          {"handles[0].motion.keyframes[1].time", "finite"});
  refused([&](HandleMotion& m) { m.keyframes[1].translation.y() = nan; },
          {"handles[0].motion.keyframes[1].translation"});
  refused([&](HandleMotion& m) { m.keyframes[0].angle = nan; },
          {"handles[0].motion.keyframes[0].angle"});
  refused([&](HandleMotion& m) { m.keyframes[1].axis = Vec3::Zero(); },
          {"handles[0].motion.keyframes[1].axis"});
  refused([&](HandleMotion& m) { m.velocity = Vec3(0, 1, 0); }, {"not both"});
  refused([&](HandleMotion& m) { m.angular_velocity = 1.0; }, {"not both"});
  // obstacles are checked the same way, under their own name
  Obstacle o;
  o.mesh = scene.bodies[0].mesh;
  o.motion = scene.handles[0].motion;
  o.motion.keyframes[1].time = 0.0;
  scene.obstacles.push_back(o);
  scene.effects.enable(Effect::contact);
  test_support::expect_error([&] { validate_scene(scene); }, Status::invalid_scene,
                             {"obstacles[0].motion.keyframes[1].time"});
}
