// Progressive collision objects (PSQ §4.6): an obstacle decimated in the shell's proportions,
// its level meshes, and its safe refinement toward its finer mesh, checked against the
// hierarchy's own rest levels and with CGAL's exact intersection test.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "mesh/intersection_check.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_validation.hpp"
#include "progressive/progressive_obstacles.hpp"

using namespace progsim;

namespace {

/// A static progressive sphere (642 vertices) and a fixed box, as scene obstacles.
Scene sphere_and_box() {
  Scene scene;
  Obstacle sphere{"sphere", make_sphere(0.25, 3), {}, 0.0, true};
  Obstacle box{"box", make_grid(0.1, 0.1, 1, 1), {}, 0.0, false};
  box.mesh.vertices.col(1).array() -= 1.0;  // far below the sphere
  scene.obstacles = {sphere, box};
  return scene;
}

const std::vector<int> kShellLevels = {100, 400, 1600};

/// The shell and obstacle faces of one mesh, to test crossings between them with CGAL.
std::size_t crossings(const Positions& shell, const Faces& shell_faces, const Positions& obstacle,
                      const Faces& obstacle_faces) {
  const TriangleMesh shell_mesh{shell, shell_faces}, obstacle_mesh{obstacle, obstacle_faces};
  const TriangleMesh all = merge_meshes({&shell_mesh, &obstacle_mesh});
  return intersecting_faces(all.vertices, all.faces).size();
}

}  // namespace

TEST(ProgressiveObstacles, LevelsFollowTheShellsProportionsAndAreValidMeshes) {
  const Scene scene = sphere_and_box();
  const ObstacleHierarchy levels(scene, kShellLevels);
  ASSERT_FALSE(levels.empty());
  ASSERT_EQ(levels.num_levels(), 3);
  const int expected[] = {161, 321, 642};  // round(642 · √(100 / 1600)), round(642 · √¼), all
  for (int level = 0; level < 3; ++level) {
    SCOPED_TRACE("level " + std::to_string(level));
    Scene at = scene;
    levels.use_level(level, at);
    const TriangleMesh& sphere = at.obstacles[0].mesh;
    EXPECT_EQ(sphere.num_vertices(), expected[level]);
    EXPECT_NO_THROW(validate_mesh(sphere, "sphere level"));
    EXPECT_EQ(intersecting_faces(sphere.vertices, sphere.faces).size(), 0u);  // CGAL
    EXPECT_EQ(sphere.vertices, levels.hierarchy().levels[level].rest.vertices);
    // Coarse vertices keep their input positions (HierarchyOptions::keep_input_positions): the
    // coarse sphere is inscribed in the fine one and cannot bulge into a shell resting on it.
    const Positions& input = scene.obstacles[0].mesh.vertices;
    for (int v = 0; v < sphere.num_vertices(); ++v) {
      bool found = false;
      for (int i = 0; i < input.rows() && !found; ++i)
        found = sphere.vertices.row(v) == input.row(i);
      ASSERT_TRUE(found) << "coarse vertex " << v << " is not at an input position";
    }
    EXPECT_EQ(at.obstacles[1].mesh.vertices, scene.obstacles[1].mesh.vertices);  // not progressive
    EXPECT_EQ(at.obstacles[1].mesh.faces, scene.obstacles[1].mesh.faces);
  }
}

TEST(ProgressiveObstacles, NoProgressiveObstacleMeansNoHierarchy) {
  Scene scene = sphere_and_box();
  scene.obstacles[0].progressive = false;
  const ObstacleHierarchy levels(scene, kShellLevels);
  EXPECT_TRUE(levels.empty());
  Scene at = scene;
  levels.use_level(0, at);
  EXPECT_EQ(at.obstacles[0].mesh.vertices, scene.obstacles[0].mesh.vertices);
}

TEST(ProgressiveObstacles, RefinementWithNothingInTheWayReachesTheFinerLevel) {
  const Scene scene = sphere_and_box();
  const ObstacleHierarchy levels(scene, kShellLevels);
  const MeshHierarchy& h = levels.hierarchy();
  const Positions& box = scene.obstacles[1].mesh.vertices;
  Positions stacked(h.levels[0].rest.num_vertices() + box.rows(), 3);
  stacked << h.levels[0].rest.vertices, box;
  const Positions shell = make_grid(0.1, 0.1, 1, 1).vertices.array() + 5.0;  // far away
  const Faces shell_faces = make_grid(0.1, 0.1, 1, 1).faces;
  SafeRefinementStats stats;
  const Positions fine = levels.refine(0, stacked, {&shell, &shell_faces, 1e-4}, 1e-3, &stats);
  ASSERT_EQ(fine.rows(), 321 + box.rows());
  // A static obstacle's prolonged target is its finer rest level (the prolongation preserves
  // rest shapes); unobstructed, every split gets there.
  EXPECT_LT((fine.topRows(321) - h.levels[1].rest.vertices).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(fine.bottomRows(box.rows()), box);
  EXPECT_EQ(stats.splits, 160);
  EXPECT_DOUBLE_EQ(stats.reached, 1.0);
}

TEST(ProgressiveObstacles, RefinementStopsWhereTheShellHugsTheCoarseObstacle) {
  // A shell wrapped tightly around the coarse sphere (its level-0 mesh scaled by 1.02; closer
  // copies already cross it, as the coarse mesh is not quite star-shaped about the centre): the
  // finer sphere bulges through it, so the refinement must stop short of its targets.
  Scene scene = sphere_and_box();
  scene.obstacles.pop_back();
  const ObstacleHierarchy levels(scene, kShellLevels);
  const TriangleMesh& coarse = levels.hierarchy().levels[0].rest;
  const Positions shell = 1.02 * coarse.vertices;
  const Faces shell_faces = coarse.faces;
  ASSERT_GT(crossings(shell, shell_faces, levels.hierarchy().levels[1].rest.vertices,
                      levels.hierarchy().levels[1].rest.faces),
            0u)
      << "the finer sphere's rest level must cross the shell for this test to mean anything";
  ASSERT_EQ(crossings(shell, shell_faces, coarse.vertices, coarse.faces), 0u);  // a valid start
  SafeRefinementStats stats;
  const Positions fine =
      levels.refine(0, coarse.vertices, {&shell, &shell_faces, 1e-4}, 1e-3, &stats);
  EXPECT_EQ(crossings(shell, shell_faces, fine, levels.hierarchy().levels[1].rest.faces), 0u);
  EXPECT_GT(stats.stopped_vertices, 0);
  EXPECT_LT(stats.reached, 1.0);
  EXPECT_GT(stats.min_gap, 0.0);
}

TEST(ProgressiveObstacles, RefusesStackedPositionsOfTheWrongSize) {
  const Scene scene = sphere_and_box();
  const ObstacleHierarchy levels(scene, kShellLevels);
  const Positions shell = Positions::Zero(3, 3);
  const Faces shell_faces = (Faces(1, 3) << 0, 1, 2).finished();
  try {
    levels.refine(0, Positions::Zero(7, 3), {&shell, &shell_faces, 0.0}, 1e-3);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::invalid_argument);
    EXPECT_NE(std::string(e.what()).find("7 obstacle positions for 165 obstacle vertices"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(levels.refine(2, Positions::Zero(646, 3), {&shell, &shell_faces, 0.0}, 1e-3), Error);
}
