#pragma once
/// @file Meshes and a distance shared by the hierarchy tests.
#include <cmath>

#include "mesh/mesh_generators.hpp"

namespace progsim::test_support {

/// A spherical cap of radius 1 over an n × n grid of side 1.2: a curved open surface.
inline TriangleMesh dome(int n) {
  TriangleMesh mesh = make_grid(1.2, 1.2, n, n);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const double x = mesh.vertices(v, 0) - 0.6, y = mesh.vertices(v, 1) - 0.6;
    mesh.vertices.row(v) << x, y, std::sqrt(1.0 - x * x - y * y);
  }
  return mesh;
}

/// max over rows of ‖a_i − b_i‖ (m).
inline double max_row_distance(const Positions& a, const Positions& b) {
  return (a - b).rowwise().norm().maxCoeff();
}

}  // namespace progsim::test_support
