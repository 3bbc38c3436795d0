// Refinement with contact never starts from an intersecting state, even when the prolonged
// target intersects: a dome (curved rest shape) whose fine vertices bulge above the coarse
// chords by the sagitta, under a small obstacle placed between the chords and the dome. The
// independent check is CGAL's exact triangle–triangle intersection test.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "contact/contact_potential.hpp"
#include "hierarchy/hierarchy_test_meshes.hpp"
#include "hierarchy/level_prolongation.hpp"
#include "mesh/intersection_check.hpp"
#include "progressive/progressive_simulation.hpp"
#include "progressive/progressive_test_scenes.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

/// Shell and obstacle faces of `mesh` (shell) and `obstacle` at the given positions as one
/// mesh; the pairs that cross (CGAL exact predicates).
std::size_t crossing_pairs(const Positions& shell, const Faces& shell_faces,
                           const TriangleMesh& obstacle) {
  Positions all(shell.rows() + obstacle.num_vertices(), 3);
  all << shell, obstacle.vertices;
  Faces faces(shell_faces.rows() + obstacle.num_faces(), 3);
  faces << shell_faces, obstacle.faces.array() + static_cast<int>(shell.rows());
  return intersecting_faces(all, faces, 1).size();
}

/// A triangle of circumradius r centred at c in the plane with normal n.
TriangleMesh small_triangle(const Vec3& c, const Vec3& n, double r) {
  const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  TriangleMesh t;
  t.vertices.resize(3, 3);
  for (int k = 0; k < 3; ++k) {
    const double a = 2.0 * 3.14159265358979323846 * k / 3.0;
    t.vertices.row(k) = (c + r * (std::cos(a) * u + std::sin(a) * v)).transpose();
  }
  t.faces.resize(1, 3);
  t.faces << 0, 1, 2;
  return t;
}

}  // namespace

TEST(ContactRefinement, NeverStartsIntersectingWhenTheProlongedTargetDoes) {
  ShellMaterial material;
  material.youngs_modulus = 1e6;
  material.thickness = 1e-4;
  Scene scene = shell_scene(dome(12), material);
  scene.effects.disable(Effect::gravity);
  scene.effects.enable(Effect::contact);
  scene.contact.dhat = 5e-4;
  Handle rim;  // the dome's border, held
  const TriangleMesh& mesh = scene.bodies[0].mesh;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const double x = mesh.vertices(v, 0), y = mesh.vertices(v, 1);
    if (std::abs(std::abs(x) - 0.6) < 1e-9 || std::abs(std::abs(y) - 0.6) < 1e-9)
      rim.vertices.push_back(v);
  }
  scene.handles.push_back(rim);
  scene.progressive.level_vertices = {30};

  // Where to put the obstacle: above the coarse face nearest the top, halfway between its
  // plane and the dome (the fine vertices inside it bulge up by the sagitta).
  const MeshHierarchy h = build_scene_hierarchy(scene);
  const TriangleMesh& coarse = h.levels[0].rest;
  int top = 0;
  double best = -1.0;
  for (int f = 0; f < coarse.num_faces(); ++f) {
    double z = 0.0;
    for (int k = 0; k < 3; ++k) z += coarse.vertices(coarse.faces(f, k), 2) / 3.0;
    if (z > best) best = z, top = f;
  }
  Vec3 a = coarse.vertices.row(coarse.faces(top, 0)), b = coarse.vertices.row(coarse.faces(top, 1)),
       c = coarse.vertices.row(coarse.faces(top, 2));
  const Vec3 centre = (a + b + c) / 3.0, normal = (b - a).cross(c - a).normalized();
  const double sagitta = 1.0 - centre.norm();  // the dome is a unit sphere about the origin
  ASSERT_GT(sagitta, 4e-3);
  Obstacle lid;
  lid.name = "lid";
  lid.mesh = small_triangle(centre + 0.5 * sagitta * normal, normal, 0.4 * (b - a).norm());
  scene.obstacles.push_back(lid);

  ProgressiveSimulation psq(scene);
  psq.step();
  const Positions preview = psq.positions(0);
  const Positions target = next_level_prolongation(psq.hierarchy(), 0)(preview);
  // The premise: the prolonged state crosses the obstacle (CGAL).
  ASSERT_GT(crossing_pairs(target, mesh.faces, lid.mesh), 0u);
  psq.refine();
  ASSERT_EQ(psq.level(), 1);
  EXPECT_EQ(crossing_pairs(psq.positions(1), mesh.faces, lid.mesh), 0u);
  EXPECT_LT(psq.records()[1].refine_reached, 1.0);  // contact stopped it short of the target
  EXPECT_GT(psq.records()[1].refine_reached, 0.0);
  psq.settle_to_equilibrium(100);
  EXPECT_EQ(crossing_pairs(psq.positions(1), mesh.faces, lid.mesh), 0u);
  EXPECT_TRUE(psq.current().dofs().allFinite());
}
