#pragma once
/// @file Two copies of a flat sheet stacked a gap apart, for contact and crossing tests.
#include "mesh/triangle_mesh.hpp"

namespace progsim::test_support {

/// `lower` and `upper` as one mesh (lower's vertices first), upper raised by `gap` along z.
inline TriangleMesh stacked_sheets(const TriangleMesh& lower, const TriangleMesh& upper,
                                   double gap) {
  const int n = lower.num_vertices();
  TriangleMesh two;
  two.vertices.resize(n + upper.num_vertices(), 3);
  two.vertices << lower.vertices, upper.vertices;
  two.vertices.bottomRows(upper.num_vertices()).col(2).array() += gap;
  two.faces.resize(lower.num_faces() + upper.num_faces(), 3);
  two.faces << lower.faces, (upper.faces.array() + n).matrix();
  return two;
}

}  // namespace progsim::test_support
