// Mesh topology: edges, boundary flags and hinges against a brute-force count from the faces,
// Euler characteristics of known surfaces, and the hinge orientation convention.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh_test_support.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

/// The same surface with vertices relabelled, faces reordered and each face's corners
/// rotated (orientation kept), all at random.
TriangleMesh shuffled(const TriangleMesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<int> label(mesh.num_vertices()), order(mesh.num_faces());
  std::iota(label.begin(), label.end(), 0);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(label.begin(), label.end(), rng);
  std::shuffle(order.begin(), order.end(), rng);
  TriangleMesh out;
  out.vertices.resize(mesh.num_vertices(), 3);
  for (int v = 0; v < mesh.num_vertices(); ++v) out.vertices.row(label[v]) = mesh.vertices.row(v);
  out.faces.resize(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const int shift = static_cast<int>(rng() % 3);
    for (int k = 0; k < 3; ++k) out.faces(f, k) = label[mesh.faces(order[f], (k + shift) % 3)];
  }
  return out;
}

}  // namespace

TEST(MeshTopology, ListsTheEdgesAndHingesOfASquareFan) {
  // The unit square as four triangles around its centre, vertex 4.
  Faces faces(4, 3);
  faces << 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4;
  const MeshTopology topology = build_topology(faces, 5);
  const std::vector<std::array<int, 2>> edges{{0, 1}, {0, 3}, {0, 4}, {1, 2},
                                              {1, 4}, {2, 3}, {2, 4}, {3, 4}};
  EXPECT_EQ(topology.edges, edges);
  EXPECT_EQ(topology.edge_on_boundary,
            (std::vector<bool>{true, true, false, true, false, true, false, false}));
  ASSERT_EQ(topology.hinges.size(), 4u);
  // The hinge on (1, 4) joins faces 0 and 1, whose other corners are 0 and 2.
  const Hinge& h = topology.hinges[1];
  EXPECT_EQ(std::minmax(h.v0, h.v1), std::minmax(1, 4));
  EXPECT_EQ(std::minmax(h.f0, h.f1), std::minmax(0, 1));
  EXPECT_EQ(std::minmax(h.v2, h.v3), std::minmax(0, 2));
  expect_consistent_topology(faces, topology);
}

TEST(MeshTopology, GridIsADisc) {
  for (const auto& [nx, ny] : std::vector<std::pair<int, int>>{{1, 1}, {3, 2}, {7, 5}}) {
    SCOPED_TRACE(::testing::Message() << nx << " × " << ny);
    const TriangleMesh grid = make_grid(2.0, 1.0, nx, ny);
    const MeshTopology topology = build_topology(grid.faces, grid.num_vertices());
    expect_consistent_topology(grid.faces, topology);
    // Horizontal, vertical and one diagonal edge per quad.
    EXPECT_EQ(static_cast<int>(topology.edges.size()), nx * (ny + 1) + ny * (nx + 1) + nx * ny);
    EXPECT_EQ(boundary_edge_count(topology), 2 * (nx + ny));
    EXPECT_EQ(euler_characteristic(grid, topology), 1);
  }
}

TEST(MeshTopology, SphereIsClosedWithEulerCharacteristicTwo) {
  for (int s = 0; s <= 3; ++s) {
    const TriangleMesh sphere = make_sphere(1.0, s);
    const MeshTopology topology = build_topology(sphere.faces, sphere.num_vertices());
    expect_consistent_topology(sphere.faces, topology);
    EXPECT_EQ(boundary_edge_count(topology), 0) << s;
    EXPECT_EQ(2 * topology.edges.size(), 3u * sphere.num_faces()) << s;
    EXPECT_EQ(topology.hinges.size(), topology.edges.size()) << s;
    EXPECT_EQ(euler_characteristic(sphere, topology), 2) << s;
  }
}

TEST(MeshTopology, TubeIsAnAnnulusAndPatchADisc) {
  const TriangleMesh tube = make_cylinder(0.5, 2.0, 2 * kPi, 9, 4);
  const MeshTopology tube_topology = build_topology(tube.faces, tube.num_vertices());
  expect_consistent_topology(tube.faces, tube_topology);
  EXPECT_EQ(euler_characteristic(tube, tube_topology), 0);
  EXPECT_EQ(boundary_edge_count(tube_topology), 2 * 9);

  const TriangleMesh patch = make_cylinder(0.5, 2.0, kPi, 9, 4);
  const MeshTopology patch_topology = build_topology(patch.faces, patch.num_vertices());
  expect_consistent_topology(patch.faces, patch_topology);
  EXPECT_EQ(euler_characteristic(patch, patch_topology), 1);
  EXPECT_EQ(boundary_edge_count(patch_topology), 2 * (9 + 4));
}

TEST(MeshTopology, DoesNotDependOnLabelsOrFaceOrder) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const TriangleMesh sphere = shuffled(make_sphere(1.0, 2), seed);
    const MeshTopology topology = build_topology(sphere.faces, sphere.num_vertices());
    expect_consistent_topology(sphere.faces, topology);
    EXPECT_EQ(euler_characteristic(sphere, topology), 2);
    const TriangleMesh grid = shuffled(make_grid(1.0, 1.0, 6, 4), seed);
    const MeshTopology grid_topology = build_topology(grid.faces, grid.num_vertices());
    expect_consistent_topology(grid.faces, grid_topology);
    EXPECT_EQ(euler_characteristic(grid, grid_topology), 1);
  }
}

TEST(MeshTopology, EmptyMeshHasNoEdges) {
  const MeshTopology topology = build_topology(Faces(0, 3), 0);
  EXPECT_TRUE(topology.edges.empty());
  EXPECT_TRUE(topology.hinges.empty());
}
