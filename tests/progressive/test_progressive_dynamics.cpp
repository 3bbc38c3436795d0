// Progressive Dynamics (PD 2024 §4, Alg. 1; PD++'s velocity-only prolongation): the preview's
// and the refined levels' motion against closed forms, their metrics against negative
// controls, and misuse of the driver.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "common/error.hpp"
#include "mesh/mesh_generators.hpp"
#include "progressive/progressive_dynamics.hpp"
#include "progressive/progressive_test_scenes.hpp"
#include "sim/contact_scene_support.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using namespace progsim::test_support;
using namespace progsim::contact_scenes;

namespace {

/// A 0.5 m cotton-like square cloth (21 × 21 vertices) in the x–y plane under gravity −z,
/// animated with h = 10 ms on three levels (30, 120, 441 vertices); nothing holds it.
Scene falling_cloth(int steps) {
  ShellMaterial cloth;
  cloth.youngs_modulus = 1e5;
  cloth.thickness = 5e-4;
  cloth.density = 300.0;
  Scene scene = shell_scene(make_grid(0.5, 0.5, 20, 20), cloth);
  scene.mode = StepMode::dynamic;
  scene.time_step = 0.01;
  scene.duration = steps * scene.time_step;
  scene.progressive.level_vertices = {30, 120};
  return scene;
}

/// The same cloth held at two corners: it swings down and folds.
Scene swinging_cloth(int steps) {
  Scene scene = falling_cloth(steps);
  Handle corners;
  corners.vertices = {0, 20};  // (0, 0) and (0.5, 0)
  scene.handles.push_back(corners);
  return scene;
}

/// Every frame of `level`: its shell and the (static) obstacles have no two faces that cross,
/// by CGAL's exact predicates.
void expect_frames_intersection_free(const ProgressiveDynamics& pd, int level) {
  const Faces& faces = pd.hierarchy().levels[level].rest.faces;
  const int n = pd.hierarchy().levels[level].rest.num_vertices();
  Positions all(n, 3);
  Faces all_faces = faces;
  for (const Obstacle& o : pd.scene().obstacles) {
    const Eigen::Index v0 = all.rows(), f0 = all_faces.rows();
    all.conservativeResize(v0 + o.mesh.num_vertices(), 3);
    all.bottomRows(o.mesh.num_vertices()) = o.mesh.vertices;
    all_faces.conservativeResize(f0 + o.mesh.num_faces(), 3);
    all_faces.bottomRows(o.mesh.num_faces()) = o.mesh.faces.array() + int(v0);
  }
  Positions x, v;
  for (int frame = 0; frame < pd.num_frames(level); ++frame) {
    pd.read_frame(level, frame, x, v);
    all.topRows(n) = x;
    const auto pairs = intersecting_faces(all, all_faces, 1);
    EXPECT_TRUE(pairs.empty()) << "level " << level << " frame " << frame << ": faces "
                               << pairs.front().a << " and " << pairs.front().b << " cross";
  }
}

}  // namespace

TEST(ProgressiveDynamics, EveryLevelFallsFreelyAsImplicitEulerDoes) {
  // Implicit Euler from rest: x^n = x^0 + g h² n(n+1)/2. An x̂ taken from the wrong frame of the
  // coarser trajectory (t+1 for t, or the level's own v and the coarse one's twice) leads or
  // lags by h·v and fails this.
  const int steps = 12;
  Scene scene = falling_cloth(steps);
  scene.solver.tolerance = 1e-12;
  ProgressiveDynamics pd(scene);
  for (int n = 0; n < steps; ++n) pd.step_preview();
  pd.refine();
  pd.refine();
  ASSERT_EQ(pd.level(), 2);
  const double h = scene.time_step, g = 9.81;
  for (int level = 0; level <= 2; ++level) {
    ASSERT_EQ(pd.num_frames(level), steps + 1);
    Positions x0, v0, x, v;
    pd.read_frame(level, 0, x0, v0);
    for (int n = 1; n <= steps; ++n) {
      pd.read_frame(level, n, x, v);
      const double drop = g * h * h * n * (n + 1) / 2.0;
      // Every vertex (uniform motion): the centre of mass and the shape alike.
      const double worst =
          ((x - x0).rowwise() - Vec3(0, 0, -drop).transpose()).cwiseAbs().maxCoeff();
      EXPECT_LT(worst, 1e-9) << "level " << level << " step " << n;
      EXPECT_NEAR(v(0, 2), -g * h * n, 1e-8) << "level " << level << " step " << n;
    }
    for (const DynamicStepRecord& r : pd.record(level).steps) EXPECT_TRUE(r.converged);
  }
}

TEST(ProgressiveDynamics, APreviewFallsAtGEverywhereOnItsProlongedMasses) {
  // The proxy's gravity through P would also pull on the offsets a(x) (a torque that bends a
  // falling coarse cloth); on the prolonged masses M_l = Uᵀm_L every coarse vertex falls at g.
  Scene scene = falling_cloth(5);
  scene.solver.tolerance = 1e-12;
  ProgressiveDynamics pd(scene);
  const Eigen::VectorXd& m0 = pd.preview().model().vertex_masses;
  const ShellModel finest = build_shell_model(scene);
  EXPECT_NEAR(m0.sum(), finest.vertex_masses.sum(), 1e-12 * m0.sum());  // U's rows sum to 1
  for (int n = 0; n < 5; ++n) {
    const StepRecord r = pd.step_preview();
    ASSERT_TRUE(r.motion.has_value());
    const double v = 9.81 * scene.time_step * (n + 1);
    EXPECT_NEAR(r.motion->kinetic_energy, 0.5 * m0.sum() * v * v, 1e-8 * m0.sum() * v * v);
  }
  Positions x0, v0, x, v;
  pd.read_frame(0, 0, x0, v0);
  pd.read_frame(0, 5, x, v);
  const Positions moved = (x - x0).rowwise() - (x - x0).row(0);
  EXPECT_LT(moved.cwiseAbs().maxCoeff(), 1e-9 * 0.5);  // no strain: a rigid translation
}

TEST(ProgressiveDynamics, VelocityOnlyPredictionIsTheMostContinuous) {
  // PD++: PD eq. 5 and PSQ per frame pull the fine positions toward the prolonged coarse ones
  // every step, which the continuity metric (VPD App. C eq. 18) must see against the
  // velocity-only prediction. Every frame of every level stays intersection-free (CGAL's exact
  // predicates).
  const int steps = 40;
  auto mean_continuity = [&](DynamicsPrediction rule) {
    Scene scene = cloth_scene(horizontal_cloth(0.6, 20, 0.2), 0.0, 0.01, steps);
    scene.obstacles.push_back(static_obstacle("sphere", make_sphere(0.15, 3), 0.0));
    scene.progressive.level_vertices = {60};
    scene.progressive.prediction = rule;
    ProgressiveDynamics pd(scene);
    for (int n = 0; n < steps; ++n) pd.step_preview();
    pd.refine();
    for (int level = 0; level <= 1; ++level) expect_frames_intersection_free(pd, level);
    double sum = 0.0;
    for (const DynamicStepRecord& r : pd.record(1).steps) sum += r.motion.continuity;
    return sum / steps;
  };
  const double velocity_only = mean_continuity(DynamicsPrediction::velocity_only);
  const double prolonged = mean_continuity(DynamicsPrediction::prolonged_positions);
  const double per_frame = mean_continuity(DynamicsPrediction::per_frame);
  std::cout << "mean continuity (eq. 18) on the finest of 2 levels: velocity_only " << velocity_only
            << ", prolonged_positions " << prolonged << ", per_frame " << per_frame << "\n";
  EXPECT_GT(prolonged, 1.3 * velocity_only);
  EXPECT_GT(per_frame, 1.3 * velocity_only);
}

TEST(ProgressiveDynamics, MisuseIsRefusedAndChangesNothing) {
  Scene scene = falling_cloth(3);
  ProgressiveDynamics pd(scene);
  expect_error([&] { pd.refine(); }, Status::wrong_call_order, {"preview at least one step"});
  Positions x, v;
  expect_error([&] { pd.read_frame(1, 0, x, v); }, Status::out_of_range,
               {"level 1", "not been computed"});
  pd.step_preview();
  expect_error([&] { pd.read_frame(0, 2, x, v); }, Status::out_of_range,
               {"frame 2", "not been computed"});
  Scene other = scene;
  other.time_step = 0.02;
  expect_error([&] { pd.update_scene(other); }, Status::invalid_argument, {"time step"});
  EXPECT_EQ(pd.scene().time_step, 0.01);
  expect_error([&] { pd.set_preview_velocities(Vector::Zero(3)); }, Status::wrong_call_order,
               {"taken steps"});
  // A cancelled refinement leaves no level behind.
  expect_error([&] { pd.refine([](int, int) { return false; }); }, Status::cancelled,
               {"cancelled at step 1 of 1"});
  EXPECT_EQ(pd.level(), 0);
  pd.refine();
  EXPECT_EQ(pd.level(), 1);
  expect_error([&] { pd.step_preview(); }, Status::wrong_call_order, {"restart()"});
  expect_error([&] { pd.update_scene(scene); }, Status::wrong_call_order, {"restart()"});
  EXPECT_EQ(pd.num_frames(0), 2);
  pd.refine();
  expect_error([&] { pd.refine(); }, Status::out_of_range, {"finest level"});
  pd.restart();
  EXPECT_EQ(pd.level(), 0);
  EXPECT_EQ(pd.num_frames(0), 1);
  Scene quasistatic = scene;
  quasistatic.mode = StepMode::quasistatic;
  quasistatic.handles.push_back({0, {0}, {}});
  expect_error([&] { ProgressiveDynamics bad(quasistatic); }, Status::invalid_scene,
               {"dynamic scenes"});
}
