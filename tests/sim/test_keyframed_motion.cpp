// Keyframed handles and obstacles in simulations: a handle sits at each key's pose at the key's
// time and holds after the last; an obstacle on keyframes sweeping a cloth leaves every frame
// intersection-free (CGAL exact predicates); and a handle jumping an edge length per step is
// moved in rounds instead of collapsing the faces next to it. A progressive obstacle on keyframes
// is carried to its scripted pose through the levels.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "common/constants.hpp"
#include "mesh/mesh_generators.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "sim/contact_scene_support.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;
using namespace progsim::contact_scenes;

namespace {

/// A 1 m × 0.5 m sheet of 8 × 4 quads in the x–y plane with membrane and bending.
Scene keyframed_sheet(StepMode mode, double time_step, int steps) {
  Scene scene;
  scene.name = "keyframed_sheet";
  scene.mode = mode;
  scene.time_step = time_step;
  scene.duration = steps * time_step;
  scene.effects.enable(Effect::membrane);
  scene.effects.enable(Effect::bending);
  scene.bodies.push_back({"sheet", make_grid(1.0, 0.5, 8, 4), {}, 0.0, 0.0});
  return scene;
}

/// The vertices of the sheet's left edge (x = 0): 5 of them, j·9 for j = 0..4.
std::vector<int> sheet_left_edge() {
  return {0, 9, 18, 27, 36};
}

}  // namespace

TEST(KeyframedMotion, AHandleSitsAtEachKeysPoseAtItsTimeAndHoldsAfterTheLast) {
  // Keys at 0, 0.3 and 0.5 s (steps 3 and 5 of 0.1 s): lifted, then lifted further and turned
  // 0.4 rad about z through the edge's middle; held over steps 6–8.
  Scene scene = keyframed_sheet(StepMode::quasistatic, 0.1, 8);
  Handle h;
  h.vertices = sheet_left_edge();
  h.motion.center = Vec3(0.0, 0.25, 0.0);
  h.motion.interpolation = Interpolation::smooth;
  h.motion.keyframes = {{0.0, Vec3::Zero(), Vec3::UnitZ(), 0.0},
                        {0.3, Vec3(0.0, 0.0, 0.05), Vec3::UnitZ(), 0.0},
                        {0.5, Vec3(0.02, 0.0, 0.1), Vec3::UnitZ(), 0.4}};
  scene.handles.push_back(h);
  const Positions rest = scene.bodies[0].mesh.vertices;
  LevelSimulation sim(scene);
  const auto key_pose = [&](int k, int v) {
    const MotionKeyframe& key = h.motion.keyframes[k];
    const Vec3 x = rest.row(v).transpose() - h.motion.center;
    return Vec3(h.motion.center + Eigen::AngleAxisd(key.angle, key.axis) * x + key.translation);
  };
  for (int step = 1; step <= 8; ++step) {
    const StepRecord r = sim.step();
    ASSERT_EQ(r.script_reached, 1.0) << "step " << step;
    ASSERT_NE(r.newton.stop, NewtonStop::non_finite) << "step " << step;
    const int key = step == 3 ? 1 : step >= 5 ? 2 : -1;  // the key at (or held after) this time
    for (int v : h.vertices) {
      const Vec3 x = sim.positions().row(v).transpose();
      EXPECT_LT((x - h.motion.position(rest.row(v).transpose(), r.time)).norm(), 1e-15);
      if (key >= 0) EXPECT_LT((x - key_pose(key, v)).norm(), 1e-12) << "step " << step;
    }
  }
  // Nothing loads the sheet, which turns freely about the held edge: it follows the edge
  // without straining, its far corner as far from the edge's ends as at rest.
  for (int end : {0, 36}) {
    const double now = (sim.positions().row(8) - sim.positions().row(end)).norm();
    EXPECT_NEAR(now, (rest.row(8) - rest.row(end)).norm(), 1e-3) << "to vertex " << end;
  }
}

TEST(KeyframedMotion, AnObstacleOnKeyframesSweepsTheClothIntersectionFree) {
  // A cloth falls on a sphere that rises under it, then slides sideways while turning about x
  // (smooth keys: the scripted rounds must stay CCD-safe through the rotation too). Every
  // frame is checked with CGAL's exact predicates, shell against itself and the sphere.
  const double radius = 0.1;
  Scene scene = cloth_scene(horizontal_cloth(0.4, 8, radius + 0.01), 0.5, 0.01, 16);
  Obstacle sphere = static_obstacle("sphere", make_sphere(radius, 1), 0.5);
  sphere.motion.interpolation = Interpolation::smooth;
  sphere.motion.keyframes = {{0.0, Vec3::Zero(), Vec3::UnitX(), 0.0},
                             {0.05, Vec3(0.0, 0.03, 0.0), Vec3::UnitX(), 0.0},
                             {0.15, Vec3(0.06, 0.03, 0.0), Vec3::UnitX(), 0.6}};
  scene.obstacles.push_back(sphere);
  LevelSimulation sim(scene);
  const std::vector<StepRecord> records = run_checked(sim);
  ASSERT_EQ(records.size(), 16u);
  EXPECT_EQ(sim.intersecting_face_pairs(), 0u);
  EXPECT_LT(records.back().contact->min_gap, scene.contact.dhat) << "the sphere met the cloth";
  // after the last key the sphere holds its pose
  const Positions& s0 = sphere.mesh.vertices;
  const Positions at = sim.obstacle_positions();
  for (Eigen::Index v = 0; v < s0.rows(); ++v)
    EXPECT_LT((at.row(v).transpose() - sphere.motion.position(s0.row(v).transpose(), 0.15)).norm(),
              1e-12);
}

TEST(KeyframedMotion, AHandleJumpingAnEdgeLengthPerStepMovesInRoundsInsteadOfCollapsing) {
  // The left edge jumps 1 and then 1.5 edge lengths (0.125 m) per step toward the free
  // vertices, in a dynamic and in a quasistatic step. Moved at once it lands on (or passes)
  // its neighbours and the faces between them collapse: the step ended 'non_finite' before
  // the handle rounds. Now each round keeps half of every face's area next to the handle.
  for (StepMode mode : {StepMode::dynamic, StepMode::quasistatic}) {
    for (double edges : {1.0, 1.5}) {
      Scene scene = keyframed_sheet(mode, 0.01, 3);
      Handle h;
      h.vertices = sheet_left_edge();
      h.motion.velocity = Vec3(edges * 0.125 / scene.time_step, 0.0, 0.0);
      scene.handles.push_back(h);
      LevelSimulation sim(scene);
      const Faces& faces = sim.model().rest.faces;
      const double rest_min = face_areas(Positions(sim.positions()), faces).minCoeff();
      for (int step = 1; step <= 3; ++step) {
        const StepRecord r = sim.step();
        const std::string where =
            std::string(mode == StepMode::dynamic ? "dynamic" : "quasistatic") + ", " +
            std::to_string(edges) + " edges, step " + std::to_string(step);
        ASSERT_TRUE(sim.dofs().allFinite()) << where;
        EXPECT_NE(r.newton.stop, NewtonStop::non_finite) << where;
        EXPECT_EQ(r.newton.stop, NewtonStop::converged) << where;
        EXPECT_EQ(r.script_reached, 1.0) << where;
        EXPECT_NEAR(sim.positions()(0, 0), edges * 0.125 * step, 1e-12) << where;
        EXPECT_GT(face_areas(Positions(sim.positions()), faces).minCoeff(), 0.1 * rest_min)
            << where;
      }
    }
  }
}

TEST(KeyframedMotion, AProgressiveObstacleOnKeyframesIsCarriedToItsPoseThroughTheLevels) {
  // The cloth settling on a progressive sphere (tests/data), the sphere now sinking 1 cm while
  // turning 0.3 rad about y over the load step: the coarse level meets its decimated copy,
  // refinement expands it, and the script rounds carry it to the keyed pose: the preview step
  // reaches its script, every level is intersection-free, the finest ends at the pose.
  Scene scene = load_scene_file(std::string(PROGSIM_TEST_DATA_DIR) + "/progressive_obstacle.json");
  Obstacle& sphere = scene.obstacles[0];
  sphere.motion.keyframes = {{0.0, Vec3::Zero(), Vec3::UnitY(), 0.0},
                             {1.0, Vec3(0.0, -0.01, 0.0), Vec3::UnitY(), 0.3}};
  ProgressiveSimulation psq(scene);
  const StepRecord step = psq.step();
  EXPECT_EQ(step.script_reached, 1.0);
  for (;;) {
    psq.settle_to_equilibrium(20);
    EXPECT_EQ(psq.current().intersecting_face_pairs(), 0u) << "level " << psq.level();
    if (psq.level() == psq.finest()) break;
    psq.refine();
  }
  const Positions at = psq.current().obstacle_positions();
  ASSERT_EQ(at.rows(), sphere.mesh.vertices.rows());
  for (Eigen::Index v = 0; v < at.rows(); ++v)
    EXPECT_LT(
        (at.row(v).transpose() - sphere.motion.position(sphere.mesh.vertices.row(v), 1.0)).norm(),
        1e-12)
        << "vertex " << v;
}
