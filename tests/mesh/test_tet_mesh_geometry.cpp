// Tet meshes: signed volumes against hand-computed values, the Kuhn box generator's counts
// and volume, and the boundary surface (closed, outward, Euler characteristic 2).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "mesh/mesh_topology.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_generators.hpp"
#include "mesh/tet_mesh_validation.hpp"
#include "mesh_test_support.hpp"
#include "tet_test_support.hpp"

using namespace progsim;
using progsim::test_support::euler_characteristic;
using progsim::test_support::expect_error;
using progsim::test_support::signed_volume;
using progsim::tet_test::cube5;
using progsim::tet_test::unit_tet;

TEST(TetMeshVolume, UnitTetIsOneSixthAndSwappingCornersNegates) {
  TetMesh mesh = unit_tet();
  EXPECT_DOUBLE_EQ(tet_signed_volumes(mesh.vertices, mesh.tets)[0], 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(tet_mesh_volume(mesh), 1.0 / 6.0);
  std::swap(mesh.tets(0, 1), mesh.tets(0, 2));
  EXPECT_DOUBLE_EQ(tet_signed_volumes(mesh.vertices, mesh.tets)[0], -1.0 / 6.0);
}

TEST(TetMeshVolume, ScaledAndShiftedTet) {
  TetMesh mesh = unit_tet();
  // Edges 2, 3 and 4 along the axes from corner (1, 1, 1): volume 2·3·4/6 = 4.
  mesh.vertices << 1, 1, 1, 3, 1, 1, 1, 4, 1, 1, 1, 5;
  EXPECT_DOUBLE_EQ(tet_mesh_volume(mesh), 4.0);
}

TEST(TetMeshVolume, FiveTetCubeFillsTheUnitCube) {
  const TetMesh mesh = cube5();
  const Eigen::VectorXd volumes = tet_signed_volumes(mesh.vertices, mesh.tets);
  for (int t = 0; t < 4; ++t) EXPECT_DOUBLE_EQ(volumes[t], 1.0 / 6.0) << "corner tet " << t;
  EXPECT_DOUBLE_EQ(volumes[4], 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(tet_mesh_volume(mesh), 1.0);
}

TEST(TetMeshBox, CountsVolumeAndPositiveTets) {
  const Vec3 size(0.5, 1.5, 2.0);
  const TetMesh mesh = make_tet_box(size, 2, 3, 4);
  EXPECT_EQ(mesh.num_vertices(), 3 * 4 * 5);
  EXPECT_EQ(mesh.num_tets(), 6 * 2 * 3 * 4);
  EXPECT_NEAR(tet_mesh_volume(mesh), 0.5 * 1.5 * 2.0, 1e-12);
  const Eigen::VectorXd volumes = tet_signed_volumes(mesh.vertices, mesh.tets);
  // Each cell is 0.25 × 0.5 × 0.5 and each of its 6 Kuhn tets a sixth of it.
  for (int t = 0; t < mesh.num_tets(); ++t)
    EXPECT_NEAR(volumes[t], 0.25 * 0.5 * 0.5 / 6.0, 1e-15) << "tet " << t;
  EXPECT_TRUE(mesh.vertices.colwise().minCoeff().isApprox(Eigen::RowVector3d(-0.25, -0.75, -1)));
  EXPECT_TRUE(mesh.vertices.colwise().maxCoeff().isApprox(Eigen::RowVector3d(0.25, 0.75, 1)));
  EXPECT_NO_THROW(validate_tet_mesh(mesh, "box"));
}

TEST(TetMeshBox, RejectsBadArguments) {
  expect_error([] { make_tet_box(Vec3(1, 1, 1), 0, 1, 1); }, Status::invalid_argument,
               {"make_tet_box"});
  expect_error([] { make_tet_box(Vec3(1, -1, 1), 1, 1, 1); }, Status::invalid_argument,
               {"positive"});
  expect_error([] { make_tet_box(Vec3(1, NAN, 1), 1, 1, 1); }, Status::invalid_argument,
               {"finite"});
}

TEST(TetMeshBoundary, BoxBoundaryIsAClosedOutwardSphere) {
  const int nx = 2, ny = 3, nz = 4;
  const Vec3 size(0.5, 1.5, 2.0);
  const TetMesh mesh = make_tet_box(size, nx, ny, nz);
  const TetBoundary boundary = extract_tet_boundary(mesh);
  const TriangleMesh& surface = boundary.surface;
  EXPECT_EQ(surface.num_faces(), 4 * (nx * ny + ny * nz + nz * nx));
  // All grid vertices but the (nx−1)(ny−1)(nz−1) inside ones.
  EXPECT_EQ(surface.num_vertices(), 3 * 4 * 5 - 1 * 2 * 3);
  EXPECT_EQ(euler_characteristic(surface, build_topology(surface.faces, surface.num_vertices())),
            2);
  EXPECT_NO_THROW(validate_mesh(surface, "box boundary"));
  EXPECT_NEAR(signed_volume(surface), 0.5 * 1.5 * 2.0, 1e-12);  // > 0: normals point out
  ASSERT_EQ(boundary.volume_vertex.size(), static_cast<std::size_t>(surface.num_vertices()));
  for (int i = 0; i < surface.num_vertices(); ++i) {
    const int v = boundary.volume_vertex[i];
    EXPECT_EQ(surface.vertices.row(i), mesh.vertices.row(v)) << "surface vertex " << i;
    const Vec3 x = surface.vertices.row(i);
    EXPECT_TRUE(((x.cwiseAbs() - size / 2).cwiseAbs().array() < 1e-12).any())
        << "surface vertex " << i << " is not on a side of the box";
    if (i > 0) EXPECT_LT(boundary.volume_vertex[i - 1], v);
  }
}

TEST(TetMeshBoundary, SingleTetFacesPointAwayFromItsCentroid) {
  const TetMesh mesh = unit_tet();
  const TetBoundary boundary = extract_tet_boundary(mesh);
  ASSERT_EQ(boundary.surface.num_faces(), 4);
  EXPECT_EQ(boundary.volume_vertex, (std::vector<int>{0, 1, 2, 3}));
  const Vec3 centroid(0.25, 0.25, 0.25);
  for (int f = 0; f < 4; ++f) {
    const Vec3 a = boundary.surface.vertices.row(boundary.surface.faces(f, 0));
    const Vec3 b = boundary.surface.vertices.row(boundary.surface.faces(f, 1));
    const Vec3 c = boundary.surface.vertices.row(boundary.surface.faces(f, 2));
    EXPECT_GT((b - a).cross(c - a).dot((a + b + c) / 3 - centroid), 0.0) << "face " << f;
  }
}

TEST(TetMeshBoundary, FiveTetCubeHasTwelveTrianglesOnItsSixSides) {
  const TetBoundary boundary = extract_tet_boundary(cube5());
  EXPECT_EQ(boundary.surface.num_faces(), 12);
  EXPECT_EQ(boundary.volume_vertex, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_NO_THROW(validate_mesh(boundary.surface, "cube boundary"));
  EXPECT_DOUBLE_EQ(signed_volume(boundary.surface), 1.0);
}
