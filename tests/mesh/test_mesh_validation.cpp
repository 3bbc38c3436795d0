// Mesh validation: every kind of malformed mesh is rejected with invalid_mesh and a message
// naming the mesh and the first offending element; slivers with a real area pass.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "mesh/mesh_validation.hpp"
#include "mesh_test_support.hpp"

using namespace progsim;
using progsim::test_support::expect_error;

namespace {

TriangleMesh make_mesh(const std::vector<Vec3>& vertices,
                       const std::vector<std::array<int, 3>>& faces) {
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<int>(vertices.size()), 3);
  for (std::size_t v = 0; v < vertices.size(); ++v) mesh.vertices.row(v) = vertices[v];
  mesh.faces.resize(static_cast<int>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    mesh.faces.row(f) << faces[f][0], faces[f][1], faces[f][2];
  return mesh;
}

/// The unit square as a fan of four counter-clockwise triangles around its centre, vertex 4.
TriangleMesh square_fan() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}},
                   {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
}

/// Two thin triangles sharing their long edge (0, 1), apexes at ±height.
TriangleMesh sliver_diamond(double height) {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, height, 0}, {0.5, -height, 0}},
                   {{0, 1, 2}, {1, 0, 3}});
}

/// Smallest interior angle over all faces (radians), by the law of cosines.
double smallest_angle(const TriangleMesh& mesh) {
  double smallest = kPi;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = mesh.vertices.row(mesh.faces(f, k));
      const Vec3 a = Vec3(mesh.vertices.row(mesh.faces(f, (k + 1) % 3))) - p;
      const Vec3 b = Vec3(mesh.vertices.row(mesh.faces(f, (k + 2) % 3))) - p;
      smallest = std::min(smallest, std::acos(a.dot(b) / (a.norm() * b.norm())));
    }
  }
  return smallest;
}

/// A Möbius strip of n quads: non-orientable, so no choice of face orientations is consistent.
TriangleMesh moebius_strip(int n) {
  std::vector<Vec3> vertices;  // vertex 2i on one rail, 2i + 1 on the other
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * kPi * i / n;
    const Vec3 centre(std::cos(phi), std::sin(phi), 0);
    const Vec3 across = 0.2 * (std::cos(phi / 2) * centre + std::sin(phi / 2) * Vec3::UnitZ());
    vertices.push_back(centre - across);
    vertices.push_back(centre + across);
  }
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    // After a full turn the strip has flipped: rail 0 continues into rail 1.
    const bool seam = i == n - 1;
    const int c = seam ? 1 : 2 * i + 2, d = seam ? 0 : 2 * i + 3;
    faces.push_back({a, c, d});
    faces.push_back({a, d, b});
  }
  return make_mesh(vertices, faces);
}

void expect_invalid(const TriangleMesh& mesh, std::initializer_list<std::string> parts) {
  expect_error([&] { validate_mesh(mesh, "cloth.obj"); }, Status::invalid_mesh, parts);
}

}  // namespace

TEST(MeshValidation, AcceptsWellFormedMeshes) {
  EXPECT_NO_THROW(validate_mesh(square_fan(), "fan"));
  EXPECT_NO_THROW(validate_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}), "tri"));
  // A closed tetrahedron: every vertex has a closed fan.
  EXPECT_NO_THROW(validate_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                          {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}),
                                "tetrahedron"));
}

TEST(MeshValidation, RejectsAMeshWithoutFaces) {
  expect_invalid(TriangleMesh{}, {"cloth.obj: ", "no faces"});
  TriangleMesh points_only = square_fan();
  points_only.faces.resize(0, 3);
  expect_invalid(points_only, {"cloth.obj: ", "no faces"});
}

TEST(MeshValidation, RejectsNonFiniteCoordinatesNamingTheVertex) {
  TriangleMesh mesh = square_fan();
  mesh.vertices(3, 1) = std::numeric_limits<double>::quiet_NaN();
  expect_invalid(mesh, {"cloth.obj: vertex 3 has a non-finite coordinate (nan)"});

  mesh = square_fan();
  mesh.vertices(2, 0) = std::numeric_limits<double>::infinity();
  expect_invalid(mesh, {"cloth.obj: vertex 2 has a non-finite coordinate (inf)"});

  mesh = square_fan();
  mesh.vertices(4, 2) = -std::numeric_limits<double>::infinity();
  expect_invalid(mesh, {"cloth.obj: vertex 4 has a non-finite coordinate (-inf)"});
}

TEST(MeshValidation, NamesTheFirstOffendingVertex) {
  TriangleMesh mesh = square_fan();
  mesh.vertices(4, 0) = std::numeric_limits<double>::quiet_NaN();
  mesh.vertices(1, 2) = std::numeric_limits<double>::infinity();
  expect_invalid(mesh, {"vertex 1 has"});
}

TEST(MeshValidation, RejectsOutOfRangeIndicesNamingTheFace) {
  TriangleMesh mesh = square_fan();
  mesh.faces(2, 1) = 40;
  expect_invalid(mesh, {"cloth.obj: face 2 references vertex 40, but the mesh has 5 vertices"});
  mesh = square_fan();
  mesh.faces(3, 0) = -1;
  expect_invalid(mesh, {"cloth.obj: face 3 references vertex -1, but the mesh has 5 vertices"});
}

TEST(MeshValidation, RejectsAFaceRepeatingAVertex) {
  TriangleMesh mesh = square_fan();
  mesh.faces.row(1) << 1, 2, 1;
  expect_invalid(mesh, {"cloth.obj: face 1 repeats a vertex: (1, 2, 1)"});
}

TEST(MeshValidation, RejectsZeroAreaFaces) {
  // An extra face on the diagonal (0, 0) – (0.5, 0.5) – (1, 1): collinear corners.
  TriangleMesh mesh = square_fan();
  mesh.faces.conservativeResize(5, 3);
  mesh.faces.row(4) << 0, 4, 2;
  expect_invalid(mesh, {"cloth.obj: face 4 is degenerate (area 0 m²)"});

  // The centre moved onto the bottom edge collapses face 0.
  mesh = square_fan();
  mesh.vertices.row(4) << 0.5, 0.0, 0.0;
  expect_invalid(mesh, {"cloth.obj: face 0 is degenerate (area 0 m²)"});
}

TEST(MeshValidation, AcceptsSliversButNotVanishingAreasAtAnyScale) {
  // Apex 4 mm above a 1 m edge: angles of about 0.46°, yet a real area; a 1 nm apex is a
  // needle of 1e-7 degrees. At 1e-15 m the area is 5e-16 of the squared diagonal, below the
  // relative threshold of 1e-14.
  const TriangleMesh sliver = sliver_diamond(4e-3);
  ASSERT_LT(smallest_angle(sliver), 1.0 * kPi / 180.0);
  const auto scaled = [](TriangleMesh mesh, double scale) {
    mesh.vertices *= scale;
    return mesh;
  };
  for (const double scale : {1e-6, 1.0, 1e6}) {
    EXPECT_NO_THROW(validate_mesh(scaled(sliver, scale), "sliver")) << "scale " << scale;
    EXPECT_NO_THROW(validate_mesh(scaled(sliver_diamond(1e-9), scale), "needle"))
        << "scale " << scale;
    expect_invalid(scaled(sliver_diamond(1e-15), scale), {"face 0 is degenerate"});
  }
}

TEST(MeshValidation, RejectsAnEdgeWithThreeFaces) {
  // A fin (4, 1, 5) standing on the interior edge (1, 4).
  TriangleMesh mesh = square_fan();
  mesh.vertices.conservativeResize(6, 3);
  mesh.vertices.row(5) << 0.5, 0.0, 1.0;
  mesh.faces.conservativeResize(5, 3);
  mesh.faces.row(4) << 4, 1, 5;
  expect_invalid(mesh, {"cloth.obj: edge (1, 4) is shared by 3 faces (non-manifold)"});
}

TEST(MeshValidation, RejectsAFlippedFace) {
  TriangleMesh mesh = square_fan();
  mesh.faces.row(2) << 3, 2, 4;  // was (2, 3, 4)
  // Face 2 now runs 2 → 4 like face 1 and 4 → 3 like face 3; (2, 4) sorts first.
  expect_invalid(mesh, {"cloth.obj: edge (2, 4) is traversed in the same direction by faces 1 "
                        "and 2 (inconsistent orientation)"});
}

TEST(MeshValidation, RejectsANonOrientableMoebiusStrip) {
  const TriangleMesh strip = moebius_strip(12);
  expect_invalid(strip, {"inconsistent orientation"});
  // The same strip cut open at the seam is orientable and valid.
  TriangleMesh cut = strip;
  cut.faces.conservativeResize(cut.num_faces() - 2, 3);
  EXPECT_NO_THROW(validate_mesh(cut, "strip"));
}

TEST(MeshValidation, RejectsBowTieVertices) {
  // Two triangles touching only at vertex 2.
  expect_invalid(
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0, 2, 0}, {1, 2, 0}}, {{0, 1, 2}, {2, 4, 3}}),
      {"cloth.obj: vertex 2 is a non-manifold (bow-tie) vertex"});
  // Two closed tetrahedra sharing their apex, vertex 3: each apex fan is a closed cycle.
  expect_invalid(
      make_mesh(
          {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 2}, {1, 0, 2}, {0, 1, 2}},
          {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {4, 5, 6}, {4, 3, 5}, {5, 3, 6}, {4, 6, 3}}),
      {"cloth.obj: vertex 3 is a non-manifold (bow-tie) vertex"});
}

TEST(MeshValidation, RejectsUnreferencedVertices) {
  TriangleMesh mesh = square_fan();
  mesh.vertices.conservativeResize(7, 3);
  mesh.vertices.row(5) << 2, 2, 2;
  mesh.vertices.row(6) << 3, 3, 3;
  expect_invalid(mesh, {"cloth.obj: vertex 5 is not referenced by any face"});
}

TEST(MeshValidation, ChecksInTheDocumentedOrder) {
  // Non-finite coordinates come before index problems...
  TriangleMesh mesh = square_fan();
  mesh.vertices(0, 0) = std::numeric_limits<double>::quiet_NaN();
  mesh.faces(3, 2) = 99;
  expect_invalid(mesh, {"vertex 0 has a non-finite coordinate"});
  // ...degenerate faces before non-manifold edges...
  mesh = square_fan();
  mesh.faces.conservativeResize(6, 3);
  mesh.faces.row(4) << 1, 4, 0;  // a third face on (1, 4) and on (0, 4)
  mesh.faces.row(5) << 0, 4, 2;  // collinear
  expect_invalid(mesh, {"face 5 is degenerate"});
  // ...and edges before unreferenced vertices.
  mesh.faces.conservativeResize(5, 3);
  mesh.vertices.conservativeResize(6, 3);
  mesh.vertices.row(5) << 9, 9, 9;
  expect_invalid(mesh, {"(non-manifold)"});
}
