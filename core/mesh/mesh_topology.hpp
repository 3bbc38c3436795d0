#pragma once
/// @file Combinatorial adjacency of a triangle mesh: unique edges and interior hinges.
#include <array>
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// An interior edge with its two incident faces, as used by hinge bending.
/// The edge runs v0 → v1 in face (v0, v1, v2); the other face is (v1, v0, v3).
struct Hinge {
  int v0, v1;  ///< edge vertices
  int v2;      ///< vertex opposite the edge in the first face
  int v3;      ///< vertex opposite the edge in the second face
  int f0, f1;  ///< the two faces
};

/// Unique edges, boundary flags and hinges of a consistently oriented manifold mesh.
struct MeshTopology {
  std::vector<std::array<int, 2>> edges;  ///< unique edges (i < j), sorted
  std::vector<bool> edge_on_boundary;     ///< per edge: has exactly one incident face
  std::vector<Hinge> hinges;              ///< one per interior edge
};

/// Builds edges and hinges. Precondition: the mesh passed validate_mesh().
MeshTopology build_topology(const Faces& faces, int num_vertices);

/// The mean length of `topology`'s edges at `positions` (0 without edges).
double mean_edge_length(const MeshTopology& topology, const Positions& positions);

}  // namespace progsim
