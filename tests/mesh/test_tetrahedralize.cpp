// Tetrahedralizing closed surfaces with CGAL Mesh_3 (VPD §3.1.2): volumes against closed forms,
// determinism, and rejection of surfaces that bound no solid.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <vector>

#include "mesh/mesh_generators.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_mesh_validation.hpp"
#include "mesh/tetrahedralize.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using progsim::test_support::expect_error;

namespace {

/// Largest distance of a boundary vertex from the nearest face plane of an axis-aligned box
/// centred at the origin with half extents `half` (0 if every vertex lies on a face).
double max_off_box(const TetMesh& mesh, const Vec3& half) {
  const TetBoundary boundary = extract_tet_boundary(mesh);
  double worst = 0.0;
  for (int v = 0; v < boundary.surface.num_vertices(); ++v) {
    const Vec3 p = boundary.surface.vertices.row(v).transpose();
    worst = std::max(worst, (half - p.cwiseAbs()).minCoeff());
  }
  return worst;
}

/// The closed sphere with one face removed: a surface with a hole.
TriangleMesh open_sphere() {
  TriangleMesh sphere = make_sphere(1.0, 1);
  TriangleMesh open;
  open.faces = sphere.faces.bottomRows(sphere.num_faces() - 1);
  open.vertices = sphere.vertices;
  return open;
}

}  // namespace

TEST(Tetrahedralize, BoxKeepsItsFlatFacesAndVolume) {
  const Vec3 size(1.0, 2.0, 0.5);
  const TetMesh mesh = tetrahedralize_surface(make_box(size));
  validate_tet_mesh(mesh, "box");
  // Protected edges keep the box's sharp edges; every boundary vertex lies on a face plane.
  EXPECT_LE(max_off_box(mesh, size / 2.0), 1e-15);
  EXPECT_NEAR(tet_mesh_volume(mesh), 1.0 * 2.0 * 0.5, 1e-9 * 1.0);
  EXPECT_GT(mesh.num_tets(), 100);
  std::printf("box 1 x 2 x 0.5: %d vertices, %d tets, volume error %.3g\n", mesh.num_vertices(),
              mesh.num_tets(), tet_mesh_volume(mesh) - 1.0);
}

TEST(Tetrahedralize, SphereVolumeApproachesTheBallsAsTheMeshRefines) {
  const double r = 0.5, ball = 4.0 / 3.0 * M_PI * r * r * r;
  const TriangleMesh sphere = make_sphere(r, 4);  // 2562 vertices: the input is near exact
  double last_error = 1.0;
  for (double cell : {0.2, 0.1, 0.05}) {
    TetrahedralizeOptions options;
    options.cell_size = cell;
    options.facet_distance = cell / 20.0;
    const TetMesh mesh = tetrahedralize_surface(sphere, options);
    validate_tet_mesh(mesh, "sphere");
    const double error = std::abs(tet_mesh_volume(mesh) - ball) / ball;
    std::printf("sphere r 0.5, cell %.3g: %d vertices, %d tets, volume rel. error %.3g\n", cell,
                mesh.num_vertices(), mesh.num_tets(), error);
    EXPECT_LT(error, 0.05);
    EXPECT_LT(error, last_error);
    last_error = error;
  }
}

TEST(Tetrahedralize, TwoRunsGiveIdenticalMeshes) {
  // Mesh_3 steps that order by address (CGAL 5.5's exuder) change with the heap's state: free
  // and keep blocks of many sizes between the runs so that the second sees other addresses.
  for (const TriangleMesh& surface : {make_sphere(0.5, 3), make_box(Vec3(1.0, 0.7, 0.4))}) {
    TetrahedralizeOptions options;
    options.cell_size = 0.1;
    const TetMesh a = tetrahedralize_surface(surface, options);
    std::vector<std::vector<char>> kept;
    for (int k = 1; k < 3000; ++k) {
      std::vector<char> block(static_cast<std::size_t>(k * 37 % 4096 + 1));
      if (k % 3 == 0) kept.push_back(std::move(block));
    }
    tetrahedralize_surface(make_sphere(0.5, 4));  // more heap churn
    const TetMesh b = tetrahedralize_surface(surface, options);
    ASSERT_EQ(a.num_vertices(), b.num_vertices());
    ASSERT_EQ(a.num_tets(), b.num_tets());
    EXPECT_TRUE(a.vertices == b.vertices);
    EXPECT_TRUE(a.tets == b.tets);
  }
}

TEST(Tetrahedralize, RejectsAnOpenSurface) {
  expect_error([] { tetrahedralize_surface(open_sphere()); }, Status::invalid_mesh,
               {"tetrahedralize", "not closed", "one face only"});
}

TEST(Tetrahedralize, RejectsANonManifoldSurface) {
  // Two boxes sharing an edge through a third face: that edge lies on three faces.
  TriangleMesh mesh = make_box(Vec3(1.0, 1.0, 1.0));
  mesh.faces.conservativeResize(mesh.num_faces() + 1, 3);
  mesh.vertices.conservativeResize(mesh.num_vertices() + 1, 3);
  mesh.vertices.row(8) << 3.0, 3.0, 3.0;
  mesh.faces.row(mesh.num_faces() - 1) << mesh.faces(0, 0), mesh.faces(0, 1), 8;
  expect_error([&] { tetrahedralize_surface(mesh); }, Status::invalid_mesh,
               {"tetrahedralize", "non-manifold"});
}

TEST(Tetrahedralize, RejectsASelfIntersectingSurface) {
  TriangleMesh mesh = make_box(Vec3(1.0, 1.0, 1.0));
  TriangleMesh shifted = mesh;
  shifted.vertices.col(0).array() += 0.5;
  expect_error(
      [&] {
        tetrahedralize_surface(merge_meshes({&mesh, &shifted}));
      },
      Status::invalid_mesh, {"tetrahedralize", "intersects itself"});
}

TEST(Tetrahedralize, RejectsOptionsOutOfRange) {
  const TriangleMesh box = make_box(Vec3(1.0, 1.0, 1.0));
  TetrahedralizeOptions options;
  options.cell_size = -1.0;
  expect_error([&] { tetrahedralize_surface(box, options); }, Status::invalid_argument,
               {"cell_size"});
  options = {};
  options.facet_angle = 40.0;
  expect_error([&] { tetrahedralize_surface(box, options); }, Status::invalid_argument,
               {"facet_angle"});
  options = {};
  options.cell_radius_edge_ratio = 1.5;
  expect_error([&] { tetrahedralize_surface(box, options); }, Status::invalid_argument,
               {"cell_radius_edge_ratio"});
  // Sizes finer than memory allows are refused before Mesh_3 runs: the unit box's diagonal is
  // √3, so a cell_size of 1e-3 would ask for about (√3 / 1e-3)³ = 5·10⁹ tets.
  options = {};
  options.cell_size = 1e-3;
  expect_error([&] { tetrahedralize_surface(box, options); }, Status::invalid_argument,
               {"cell_size", "too fine"});
  options = {};
  options.facet_distance = 1e-9;
  expect_error([&] { tetrahedralize_surface(box, options); }, Status::invalid_argument,
               {"facet_distance", "too fine"});
}

TEST(Tetrahedralize, ARunPastItsTimeLimitIsStoppedWithAnErrorAndWritesNothing) {
  // Mesh_3's refinement can cycle without end on some surfaces; the time limit stops it through
  // Mesh_3's stop flag. A sphere at cell 0.02 (about 10⁵ tets) takes seconds, past 10 ms.
  const TriangleMesh sphere = make_sphere(0.5, 4);
  TetrahedralizeOptions options;
  options.cell_size = 0.02;
  options.time_limit = 0.01;
  const auto before = std::distance(std::filesystem::directory_iterator("."), {});
  expect_error([&] { tetrahedralize_surface(sphere, options); }, Status::numerical_failure,
               {"did not finish within", "time_limit"});
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator("."), {}), before);
  options.time_limit = 0.0;
  expect_error([&] { tetrahedralize_surface(sphere, options); }, Status::invalid_argument,
               {"time_limit"});
}
