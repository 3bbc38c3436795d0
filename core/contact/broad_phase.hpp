#pragma once
/// @file Broad phase of contact: the primitive pairs that may come within the activation gap
/// during a step (IPC, Li et al. 2020, §4.1), by a uniform grid (spatial hash) of axis-aligned
/// boxes.
#include <array>
#include <cstddef>
#include <vector>

#include "contact/collision_mesh.hpp"

namespace progsim {

/// Candidate pairs in collision-mesh indices.
struct CandidateSet {
  std::vector<std::array<int, 2>> vertex_face;  ///< (vertex, face)
  std::vector<std::array<int, 2>> edge_edge;    ///< (edge a, edge b), a < b

  std::size_t size() const { return vertex_face.size() + edge_edge.size(); }
};

/// All vertex–face and edge–edge pairs of `mesh` whose boxes overlap, each box spanning its
/// primitive at positions p0 and p1 (the start and end of a linear motion; p1 may equal p0)
/// grown by `inflation` (m) on every side. Pairs that share a vertex and pairs of two obstacle
/// primitives are left out. Boxes are binned in a uniform grid whose cell is the mean edge-box
/// size; each overlapping pair is reported from one cell only; OpenMP-parallel over primitives.
/// The output is sorted, so it does not depend on the thread count.
/// With `moving` (one flag per collision vertex, non-zero for moving), only the pairs with a
/// moving vertex are reported: a pair of still vertices keeps its distance, so a solve or an
/// advancement that moves a few vertices need not pay for the rest of the mesh.
/// @param p0, p1 (|V_collision| × 3) positions
/// @throws Error(invalid_argument) if `moving` has the wrong size
void find_candidates(const CollisionMesh& mesh, const Positions& p0, const Positions& p1,
                     double inflation, CandidateSet& out,
                     const std::vector<char>* moving = nullptr);

}  // namespace progsim
