// Mesh generators: counts, positions and orientation as documented, valid meshes, and areas
// against closed-form values (exact polyhedral areas, and convergence to the smooth surface).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh_test_support.hpp"

using namespace progsim;
using progsim::test_support::expect_error;
using progsim::test_support::faces_per_edge;
using progsim::test_support::signed_volume;

namespace {

/// Unnormalised normal of face f (twice its area times the unit normal).
Vec3 face_normal(const TriangleMesh& mesh, int f) {
  const Vec3 a = mesh.vertices.row(mesh.faces(f, 0));
  const Vec3 b = mesh.vertices.row(mesh.faces(f, 1));
  const Vec3 c = mesh.vertices.row(mesh.faces(f, 2));
  return (b - a).cross(c - a);
}

Vec3 face_centroid(const TriangleMesh& mesh, int f) {
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < 3; ++k) sum += mesh.vertices.row(mesh.faces(f, k)).transpose();
  return sum / 3.0;
}

double total_area(const TriangleMesh& mesh) {
  return face_areas(mesh.vertices, mesh.faces).sum();
}

/// Smallest distance between two distinct vertices (brute force).
double closest_vertex_pair(const TriangleMesh& mesh) {
  double closest = std::numeric_limits<double>::infinity();
  for (int a = 0; a < mesh.num_vertices(); ++a)
    for (int b = a + 1; b < mesh.num_vertices(); ++b)
      closest = std::min(closest, (mesh.vertices.row(a) - mesh.vertices.row(b)).norm());
  return closest;
}

}  // namespace

TEST(MeshGenerators, GridHasTheDocumentedLayout) {
  const int nx = 5, ny = 3;
  const double width = 2.0, height = 0.75;
  const TriangleMesh grid = make_grid(width, height, nx, ny);
  ASSERT_EQ(grid.num_vertices(), (nx + 1) * (ny + 1));
  ASSERT_EQ(grid.num_faces(), 2 * nx * ny);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      EXPECT_LT((grid.vertices.row(j * (nx + 1) + i) -
                 Eigen::RowVector3d(width * i / nx, height * j / ny, 0.0))
                    .norm(),
                1e-15)
          << i << ", " << j;
  EXPECT_EQ(grid.vertices.row(grid.num_vertices() - 1), Eigen::RowVector3d(width, height, 0.0));
  for (int f = 0; f < grid.num_faces(); ++f) EXPECT_GT(face_normal(grid, f).z(), 0.0) << f;
  EXPECT_NEAR(total_area(grid), width * height, 1e-14);
  EXPECT_NO_THROW(validate_mesh(grid, "grid"));
}

TEST(MeshGenerators, GridDiagonalsAlternate) {
  const int nx = 4, ny = 3;
  const TriangleMesh grid = make_grid(1.0, 1.0, nx, ny);
  const auto edges = faces_per_edge(grid.faces);
  const auto index = [&](int i, int j) { return j * (nx + 1) + i; };
  // +1 if quad (i, j) is cut from (i, j) to (i+1, j+1), −1 if from (i+1, j) to (i, j+1).
  const auto diagonal = [&](int i, int j) {
    const bool rising = edges.count({index(i, j), index(i + 1, j + 1)}) == 1;
    const bool falling = edges.count({index(i + 1, j), index(i, j + 1)}) == 1;
    EXPECT_NE(rising, falling) << "quad " << i << ", " << j << " needs exactly one diagonal";
    return rising ? 1 : -1;
  };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx) {
        EXPECT_EQ(diagonal(i, j), -diagonal(i + 1, j)) << i << ", " << j;
      }
      if (j + 1 < ny) {
        EXPECT_EQ(diagonal(i, j), -diagonal(i, j + 1)) << i << ", " << j;
      }
    }
  }
}

TEST(MeshGenerators, IcosahedronIsRegular) {
  const double r = 2.5;
  const TriangleMesh ico = make_sphere(r, 0);
  ASSERT_EQ(ico.num_vertices(), 12);
  ASSERT_EQ(ico.num_faces(), 20);
  // Edge of the regular icosahedron of circumradius r: 4r / sqrt(10 + 2√5).
  const double edge = 4.0 * r / std::sqrt(10.0 + 2.0 * std::sqrt(5.0));
  const auto edges = faces_per_edge(ico.faces);
  EXPECT_EQ(edges.size(), 30u);
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 2);
    EXPECT_NEAR((ico.vertices.row(e[0]) - ico.vertices.row(e[1])).norm(), edge, 1e-12);
  }
}

TEST(MeshGenerators, SphereHasTheDocumentedCountsRadiusAndOrientation) {
  const double r = 0.3;
  for (int s = 0; s <= 4; ++s) {
    SCOPED_TRACE(::testing::Message() << "subdivisions " << s);
    const TriangleMesh sphere = make_sphere(r, s);
    const int four_s = 1 << (2 * s);
    ASSERT_EQ(sphere.num_vertices(), 10 * four_s + 2);
    ASSERT_EQ(sphere.num_faces(), 20 * four_s);
    for (int v = 0; v < sphere.num_vertices(); ++v)
      ASSERT_NEAR(sphere.vertices.row(v).norm(), r, 1e-15) << v;
    for (int f = 0; f < sphere.num_faces(); ++f)
      ASSERT_GT(face_normal(sphere, f).dot(face_centroid(sphere, f)), 0.0) << f;
    EXPECT_GT(signed_volume(sphere), 0.0);
    EXPECT_NO_THROW(validate_mesh(sphere, "sphere"));
  }
}

TEST(MeshGenerators, SphereAreaAndVolumeConvergeToTheRoundSphere) {
  const double r = 0.3;
  const double area = 4.0 * kPi * r * r, volume = 4.0 / 3.0 * kPi * r * r * r;
  double previous = std::numeric_limits<double>::infinity();
  for (int s = 0; s <= 5; ++s) {
    const TriangleMesh sphere = make_sphere(r, s);
    const double error = std::abs(total_area(sphere) / area - 1.0);
    // Second-order convergence: the error shrinks by about 4 per subdivision.
    EXPECT_LT(error, previous / 3.0) << s;
    previous = error;
    EXPECT_LT(total_area(sphere), area) << "an inscribed polyhedron has less area";
    EXPECT_LT(signed_volume(sphere), volume);
  }
  EXPECT_LT(previous, 2e-3);
  EXPECT_NEAR(signed_volume(make_sphere(r, 5)) / volume, 1.0, 3e-3);
}

TEST(MeshGenerators, CylinderPatchHasTheDocumentedLayout) {
  const double r = 0.4, length = 1.5, angle = 0.6 * kPi;
  const int na = 8, nl = 3;
  const TriangleMesh patch = make_cylinder(r, length, angle, na, nl);
  ASSERT_EQ(patch.num_vertices(), (na + 1) * (nl + 1));
  ASSERT_EQ(patch.num_faces(), 2 * na * nl);
  for (int j = 0; j <= nl; ++j) {
    for (int i = 0; i <= na; ++i) {
      const double theta = angle * i / na;
      EXPECT_LT((patch.vertices.row(j * (na + 1) + i) -
                 Eigen::RowVector3d(r * std::sin(theta), length * j / nl, r * std::cos(theta)))
                    .norm(),
                1e-15)
          << i << ", " << j;
    }
  }
  for (int f = 0; f < patch.num_faces(); ++f) {
    const Vec3 c = face_centroid(patch, f);
    EXPECT_GT(face_normal(patch, f).dot(Vec3(c.x(), 0.0, c.z())), 0.0) << "face " << f;
  }
  EXPECT_NO_THROW(validate_mesh(patch, "patch"));
}

TEST(MeshGenerators, FullCylinderWeldsItsSeam) {
  const double r = 0.25, length = 0.8;
  const int na = 12, nl = 5;
  // 360° converted to radians, as a scene file would, closes the tube too.
  for (const double angle : {2.0 * kPi, 360.0 * kPi / 180.0}) {
    const TriangleMesh tube = make_cylinder(r, length, angle, na, nl);
    ASSERT_EQ(tube.num_vertices(), na * (nl + 1));
    ASSERT_EQ(tube.num_faces(), 2 * na * nl);
    // No duplicated seam vertex: every pair is at least a fraction of a ring chord apart.
    EXPECT_GT(closest_vertex_pair(tube), 0.5 * std::min(length / nl, 2 * r * std::sin(kPi / na)));
    for (int v = 0; v < tube.num_vertices(); ++v) {
      const auto p = tube.vertices.row(v);
      EXPECT_NEAR(std::hypot(p.x(), p.z()), r, 1e-15);
    }
    EXPECT_NO_THROW(validate_mesh(tube, "tube"));
  }
}

TEST(MeshGenerators, CylinderAreaIsExactForFlatStripsAndConverges) {
  const double r = 0.7, length = 2.0;
  for (const double angle : {0.5 * kPi, kPi, 2.0 * kPi}) {
    for (const int na : {3, 10, 1000}) {
      const TriangleMesh mesh = make_cylinder(r, length, angle, na, 4);
      // Each strip is a flat rectangle: chord × length.
      const double chord = 2.0 * r * std::sin(angle / (2.0 * na));
      EXPECT_NEAR(total_area(mesh), na * chord * length, 1e-12) << angle << ", " << na;
    }
    const double smooth = r * angle * length;
    EXPECT_NEAR(total_area(make_cylinder(r, length, angle, 1000, 2)) / smooth, 1.0, 1e-5);
  }
}

TEST(MeshGenerators, RejectsNonsenseArguments) {
  const auto expect_invalid_argument = [](auto&& make) {
    expect_error(make, Status::invalid_argument, {});
  };
  expect_invalid_argument([] { make_grid(1.0, 1.0, 0, 3); });
  expect_invalid_argument([] { make_grid(-1.0, 1.0, 2, 3); });
  expect_invalid_argument([] { make_grid(1.0, std::numeric_limits<double>::quiet_NaN(), 2, 3); });
  expect_invalid_argument([] { make_sphere(0.0, 2); });
  expect_invalid_argument([] { make_sphere(1.0, -1); });
  expect_invalid_argument([] { make_sphere(1.0, 13); });
  expect_invalid_argument([] { make_cylinder(1.0, 1.0, 7.0, 8, 2); });
  expect_invalid_argument([] { make_cylinder(1.0, 1.0, 0.0, 8, 2); });
  expect_invalid_argument([] { make_cylinder(1.0, 1.0, 2.0 * kPi, 2, 2); });
  expect_invalid_argument([] { make_cylinder(1.0, 1.0, kPi, 8, 0); });
  expect_invalid_argument([] { make_cylinder(0.0, 1.0, kPi, 8, 2); });
}
