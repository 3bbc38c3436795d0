// Rotation supports (issue 30 §2): a handle whose group turns with its script and translates
// freely. Checked against beam theory: a fixed–guided beam (the guided end keeps its slope and
// moves freely) and Sze, Liu & Lo (2004) §3.2's strip rolled into a circle, here by turning its
// end instead of applying the end moment, with the moment read from the support's reaction.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "common/constants.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "support/expect_error.hpp"
#include "support/sze_strip.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

/// Sze's strip (support/sze_strip.hpp) with nx cells, mid-edge bending (bisected normals
/// unless `model` says fitted ones). Mid-edge bending
/// holds a two-column group's rotation halfway between its columns (see
/// test_bending_convergence.cpp), so the mesh runs from −a/2 to L + a/2 (a the cell size): the
/// clamp's columns at ∓a/2 and the end group's at L ∓ a/2 leave a free length of L between
/// x = 0 and x = L. The end group is a rotation support free to translate.
Scene strip_scene(int nx, int steps, BendingModel model = BendingModel::midedge) {
  const double a = kSzeLength / (nx - 1);
  Scene scene =
      sze_strip_scene("rotation_support", -0.5 * a, kSzeLength + 0.5 * a, nx, model, 1.0 / steps);
  Handle clamp, end;
  clamp.vertices = sze_vertices_below(scene, a);
  end.vertices = sze_vertices_above(scene, kSzeLength - a);
  end.support = HandleSupport::rotation;
  end.axes = 0;  // a free translation
  end.motion.center = Vec3(kSzeLength, 0, 0);
  scene.handles = {clamp, end};
  return scene;
}

/// Mean position of the handle's vertices (the end group's centroid is the free length's end).
Vec3 centroid(const LevelSimulation& sim, const Handle& handle) {
  Vec3 sum = Vec3::Zero();
  for (int v : handle.vertices) sum += sim.positions().row(v).transpose();
  return sum / static_cast<double>(handle.vertices.size());
}

}  // namespace

TEST(RotationSupport, GuidedEndOfAFixedGuidedBeamDeflectsAndCarriesPLOverTwo) {
  // Fixed–guided beam (Roark, Table 8.1 case 1e): an end load P at the guided end gives
  // δ = P L³ / (12 E I) and moments P L / 2 at both ends; the guided end's force is 0.
  Scene scene = strip_scene(40, 1);
  const double p = 0.012;  // δ / L = 1e-3: small deflection
  Load load;
  load.vertices = scene.handles[1].vertices;
  load.force = Vec3(0, 0, -p);
  load.distribution = LoadDistribution::area;
  scene.loads.push_back(load);
  LevelSimulation sim(scene);
  const StepRecord r = sim.step();
  ASSERT_EQ(r.newton.stop, NewtonStop::converged) << stop_name(r.newton.stop);
  const double expected = p * std::pow(kSzeLength, 3) / (12.0 * kSzeBendingStiffness);
  const Vec3 end = centroid(sim, scene.handles[1]);
  std::printf(
      "[ guided   ] deflection %.6f (beam theory %.6f), end moments %.5f %.5f (PL/2 %.5f)\n",
      -end.z(), expected, r.reactions[0].moment.y(), r.reactions[1].moment.y(),
      0.5 * p * kSzeLength);
  EXPECT_NEAR(-end.z() / expected, 1.0, 0.01);
  ASSERT_EQ(r.reactions.size(), 2u);
  // The guided end is free to translate: its support supplies no force, only the moment.
  EXPECT_LT(r.reactions[1].force.norm(), 1e-6 * p);
  EXPECT_NEAR(std::abs(r.reactions[1].moment.y()), 0.5 * p * kSzeLength,
              0.01 * 0.5 * p * kSzeLength);
  EXPECT_NEAR(r.reactions[0].force.z(), p, 1e-6 * p);  // the clamp carries the whole load
  // The end group kept its shape: every vertex moved by the same translation.
  const Vec3 shift = (sim.positions().row(scene.handles[1].vertices[0]) -
                      scene.bodies[0].mesh.vertices.row(scene.handles[1].vertices[0]))
                         .transpose();
  for (int v : scene.handles[1].vertices) {
    const Vec3 moved =
        (sim.positions().row(v) - scene.bodies[0].mesh.vertices.row(v)).transpose() - shift;
    EXPECT_LT(moved.norm(), 1e-12) << "vertex " << v;
  }
}

TEST(RotationSupport, TurningTheEndRollsTheStripIntoSzeArcs) {
  // Sze, Liu & Lo 2004 §3.2: an end moment M rolls the strip into an arc of curvature M / E I,
  // a full circle at M_max = 2π E I / L; the tip is at (L sin θ / θ, L (1 − cos θ) / θ) with
  // θ = M L / E I. Here the end group turns through θ (16 quasistatic steps to 2π) and the
  // moment is its support's reaction; asserted within 2 % (tip, of L; moment) at M / M_max =
  // 0.25, 0.5 and 1 (issue 31's tolerance), with bisected and with fitted mid-edge normals,
  // and with fitted ones on the strip with its interior vertices moved by up to 0.2 cell.
  // Bisected normals on that jittered strip (measured, not run): the moment 4.3 % and 4.2 %
  // high at 0.25 and 0.5, the tip 0.075 off at 0.5, then a step that did not converge.
  const int steps = 16;
  const std::pair<BendingModel, bool> cases[] = {{BendingModel::midedge, false},
                                                 {BendingModel::midedge_fitted, false},
                                                 {BendingModel::midedge_fitted, true}};
  for (const auto& [model, jittered] : cases) {
    SCOPED_TRACE(model == BendingModel::midedge ? "midedge" : "midedge_fitted");
    SCOPED_TRACE(jittered ? "jittered" : "grid");
    Scene scene = strip_scene(40, steps, model);
    if (jittered) {  // interior vertices between the groups moved in-plane by up to 0.2 cell
      Positions& v = scene.bodies[0].mesh.vertices;
      const double a = kSzeLength / 39.0;
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> noise(-0.2 * a, 0.2 * a);
      for (int i = 0; i < v.rows(); ++i)
        if (v(i, 0) > 1.5 * a && v(i, 0) < kSzeLength - 1.5 * a && v(i, 1) > 1e-9 &&
            v(i, 1) < kSzeWidth - 1e-9) {
          v(i, 0) += noise(rng);
          v(i, 1) += noise(rng);
        }
    }
    scene.handles[1].motion.axis = Vec3(0, -1, 0);  // turns the end upward (+z)
    scene.handles[1].motion.angular_velocity = 2.0 * kPi;
    // On the jittered strip at the strip's tolerance 1e-9, step 14 (θ = 1.75π) stalled at
    // ‖∇E‖ = 4.7e-7 through 5000 Newton iterations (steps 1–13 took 17–20 each): a floor of
    // the fitted normals' gradient there, not yet understood (issue 31's note).
    if (jittered) scene.solver.tolerance = 1e-6;
    LevelSimulation sim(scene);
    std::printf("[ sze 3.2  ] %6s %9s %9s %9s %9s %9s %9s\n", "M/Mmax", "x", "x exact", "z",
                "z exact", "M", "M exact");
    for (int s = 1; s <= steps; ++s) {
      const StepRecord r = sim.step();
      ASSERT_EQ(r.newton.stop, NewtonStop::converged)
          << "step " << s << ": " << stop_name(r.newton.stop);
      if (s % 4 != 0 || s == 12) continue;
      const double theta = 2.0 * kPi * s / steps;
      const Vec3 tip = centroid(sim, scene.handles[1]);
      const Vec3 exact(kSzeLength * std::sin(theta) / theta, 0.5 * kSzeWidth,
                       kSzeLength * (1.0 - std::cos(theta)) / theta);
      const double moment = std::abs(r.reactions[1].moment.y());
      const double exact_moment = kSzeBendingStiffness * theta / kSzeLength;
      std::printf("[ sze 3.2  ] %6.2f %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f\n", theta / (2 * kPi),
                  tip.x(), exact.x(), tip.z(), exact.z(), moment, exact_moment);
      EXPECT_LT((tip - exact).norm(), 0.02 * kSzeLength) << "M/Mmax = " << theta / (2 * kPi);
      EXPECT_NEAR(moment / exact_moment, 1.0, 0.02) << "M/Mmax = " << theta / (2 * kPi);
      EXPECT_LT(r.reactions[1].force.norm(), 1e-3 * exact_moment / kSzeLength);
    }
  }
}

TEST(RotationSupport, AKeyframedPoseHeldFromTheStartIsReachedInTheFirstSteps) {
  // One key at t = 0 turning the end by π/2: the group embodies its rest pose until the first
  // step, which turns it there (and no later step turns it again), so the strip ends on Sze's
  // arc of θ = π/2.
  Scene scene = strip_scene(40, 2);
  MotionKeyframe key;
  key.axis = Vec3(0, -1, 0);
  key.angle = 0.5 * kPi;
  scene.handles[1].motion.keyframes = {key};
  LevelSimulation sim(scene);
  for (int s = 0; s < 2; ++s) ASSERT_EQ(sim.step().newton.stop, NewtonStop::converged);
  const double theta = 0.5 * kPi;
  const Vec3 exact(kSzeLength * std::sin(theta) / theta, 0.5 * kSzeWidth,
                   kSzeLength * (1.0 - std::cos(theta)) / theta);
  EXPECT_LT((centroid(sim, scene.handles[1]) - exact).norm(), 0.02 * kSzeLength);
}

TEST(RotationSupport, AFreelyFallingGroupKeepsItsShapeAndFallsAtG) {
  // Dynamic: a rotation support held still (no script) on a strip with nothing else holding it
  // translates freely, so the strip falls as a rigid body would: implicit Euler from rest gives
  // the centre of mass at −g h² n(n+1)/2 after n steps, and the group never turns.
  Scene scene = strip_scene(20, 1);
  scene.mode = StepMode::dynamic;
  scene.time_step = 0.01;
  scene.effects.enable(Effect::gravity);
  scene.gravity = Vec3(0, 0, -9.81);
  scene.handles.erase(scene.handles.begin());  // no clamp
  LevelSimulation sim(scene);
  const Vec3 start = sim.center_of_mass();
  const int n = 10;
  for (int s = 0; s < n; ++s) ASSERT_EQ(sim.step().newton.stop, NewtonStop::converged);
  const double h = scene.time_step;
  const double expected = -9.81 * h * h * n * (n + 1) / 2.0;
  EXPECT_NEAR(sim.center_of_mass().z() - start.z(), expected, 1e-6 * std::abs(expected));
  const Handle& group = scene.handles[0];
  const Positions& rest = scene.bodies[0].mesh.vertices;
  const Vec3 shift =
      (sim.positions().row(group.vertices[0]) - rest.row(group.vertices[0])).transpose();
  for (int v : group.vertices)
    EXPECT_LT(((sim.positions().row(v) - rest.row(v)).transpose() - shift).norm(), 1e-12);
}

TEST(RotationSupport, SceneKeysDefaultsAndRefusals) {
  const std::string body =
      R"("bodies": [{"name": "s", "mesh": {"generator": "grid", "width": 1, "height": 1,
                     "nx": 4, "ny": 4}}])";
  const auto scene_with = [&](const std::string& handle, const std::string& extra) {
    return R"({"simulation": {"mode": "quasistatic"}, "effects": ["membrane"], )" + body +
           R"(, "handles": [{"body": "s", "vertices": [0, 1, 5, 6])" + handle + "}]" + extra + "}";
  };
  const Scene rotation = parse_scene(scene_with(R"(, "support": "rotation")", ""), ".");
  EXPECT_EQ(rotation.handles[0].support, HandleSupport::rotation);
  EXPECT_EQ(rotation.handles[0].axes, 0u) << "a rotation support translates freely by default";
  const Scene guided = parse_scene(scene_with(R"(, "support": "rotation", "axes": "x")", ""), ".");
  EXPECT_EQ(guided.handles[0].axes, unsigned{handle_axis_x});
  EXPECT_EQ(parse_scene(scene_with("", ""), ".").handles[0].support, HandleSupport::position);
  expect_error([&] { parse_scene(scene_with(R"(, "axes": "")", ""), "."); }, Status::invalid_scene,
               {"handles[0].axes", "rotation"});
  expect_error([&] { parse_scene(scene_with(R"(, "support": "hinge")", ""), "."); },
               Status::invalid_scene, {"support", "hinge", "rotation"});
  expect_error(
      [&] {
        parse_scene(scene_with(R"(, "support": "rotation")", R"(, "progressive": {"levels": [9]})"),
                    ".");
      },
      Status::unsupported, {"handles[0]", "rotation support", "direct"});
  // In code: the same refusal of a position support without an axis.
  Scene no_axis = rotation;
  no_axis.handles[0].support = HandleSupport::position;
  expect_error([&] { validate_scene(no_axis); }, Status::invalid_scene, {"handles[0]", "axes 0"});
}
