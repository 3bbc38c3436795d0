#pragma once
/// @file Helpers shared by the mesh tests: expect_error (support/expect_error.hpp) and a
/// brute-force topology check that recomputes edges from the faces with std::map,
/// independently of build_topology().
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <initializer_list>
#include <map>
#include <string>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh/triangle_mesh.hpp"
#include "support/expect_error.hpp"

namespace progsim::test_support {

/// Number of faces on each undirected edge (i < j), counted straight from the faces.
inline std::map<std::array<int, 2>, int> faces_per_edge(const Faces& faces) {
  std::map<std::array<int, 2>, int> count;
  for (int f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  return count;
}

/// True if face f is (a, b, c) up to a cyclic rotation (same orientation).
inline bool face_is(const Faces& faces, int f, int a, int b, int c) {
  for (int k = 0; k < 3; ++k)
    if (faces(f, k) == a && faces(f, (k + 1) % 3) == b && faces(f, (k + 2) % 3) == c) return true;
  return false;
}

/// Checks edges, boundary flags and hinges of `topology` against a brute-force count, and the
/// hinge orientation convention: edge v0 → v1 in face (v0, v1, v2), other face (v1, v0, v3).
inline void expect_consistent_topology(const Faces& faces, const MeshTopology& topology) {
  const std::map<std::array<int, 2>, int> count = faces_per_edge(faces);
  ASSERT_EQ(topology.edges.size(), count.size());
  ASSERT_EQ(topology.edge_on_boundary.size(), count.size());
  std::size_t e = 0, interior = 0;
  for (const auto& [edge, n] : count) {  // std::map iterates in sorted order
    EXPECT_EQ(topology.edges[e], edge) << "edge " << e;
    EXPECT_EQ(topology.edge_on_boundary[e], n == 1) << "edge " << e;
    interior += n == 2;
    ++e;
  }
  ASSERT_EQ(topology.hinges.size(), interior);
  std::map<std::array<int, 2>, int> hinges_per_edge;
  for (const Hinge& h : topology.hinges) {
    EXPECT_TRUE(face_is(faces, h.f0, h.v0, h.v1, h.v2))
        << "hinge (" << h.v0 << ", " << h.v1 << ") face " << h.f0;
    EXPECT_TRUE(face_is(faces, h.f1, h.v1, h.v0, h.v3))
        << "hinge (" << h.v0 << ", " << h.v1 << ") face " << h.f1;
    EXPECT_NE(h.f0, h.f1);
    ++hinges_per_edge[{std::min(h.v0, h.v1), std::max(h.v0, h.v1)}];
  }
  for (const auto& [edge, n] : hinges_per_edge) {
    EXPECT_EQ(n, 1) << "edge (" << edge[0] << ", " << edge[1] << ") has several hinges";
    EXPECT_EQ(count.at(edge), 2) << "hinge on a non-interior edge";
  }
}

/// V − E + F.
inline int euler_characteristic(const TriangleMesh& mesh, const MeshTopology& topology) {
  return mesh.num_vertices() - static_cast<int>(topology.edges.size()) + mesh.num_faces();
}

/// Number of boundary edges.
inline int boundary_edge_count(const MeshTopology& topology) {
  return static_cast<int>(
      std::count(topology.edge_on_boundary.begin(), topology.edge_on_boundary.end(), true));
}

/// Enclosed volume by the divergence theorem, Σ a · (b × c) / 6: positive for a closed
/// mesh with outward normals.
inline double signed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 a = mesh.vertices.row(mesh.faces(f, 0));
    const Vec3 b = mesh.vertices.row(mesh.faces(f, 1));
    const Vec3 c = mesh.vertices.row(mesh.faces(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

}  // namespace progsim::test_support
