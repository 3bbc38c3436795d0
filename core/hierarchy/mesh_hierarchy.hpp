#pragma once
/// @file A multiresolution hierarchy of a triangle mesh (PSQ §4.1): the user's mesh and its
/// decimated levels, the intrinsic maps between them, the collapse records that refine one
/// level into the next, and the batches in which those refinements can run in parallel.
#include <array>
#include <vector>

#include "hierarchy/surface_anchor.hpp"
#include "mesh/triangle_mesh.hpp"

namespace progsim {

/// A face as three input-mesh vertex ids, oriented like the mesh.
using FaceCorners = std::array<int, 3>;

/// One edge collapse of the decimation: `removed` merged into `kept` (input-mesh vertex ids).
/// Undoing it (a vertex split) turns the faces `after` back into the faces `before`.
struct CollapseRecord {
  int removed = -1;
  int kept = -1;
  std::vector<FaceCorners> before;  ///< faces around removed ∪ kept before the collapse
  std::vector<FaceCorners> after;   ///< faces around kept after the collapse
};

/// One level: its rest mesh (the decimated geometry when the level was reached) and, per
/// level vertex, the input-mesh vertex it continues.
struct HierarchyLevel {
  TriangleMesh rest;
  std::vector<int> input_vertex;  ///< (|V_l|), increasing
};

/// Levels 0 (coarsest) … L (the user's mesh, L = levels.size() − 1).
struct MeshHierarchy {
  std::vector<HierarchyLevel> levels;
  /// to_next[l] (l < L): each vertex of level l+1 anchored on a face of level l (U^l_{l+1}).
  std::vector<SurfaceAnchors> to_next;
  /// to_finest[l] (l < L): each vertex of level L anchored on a face of level l (U^l). Each
  /// finest vertex is tracked through every collapse down to one face of level l, so U^l has at
  /// most 3 entries per row: the composition of the per-level piecewise-linear maps, rather
  /// than PSQ §4.3.1's matrix product U^{L−1}_L ⋯ U^l_{l+1}, whose rows spread over several
  /// faces (denser, and equal only where the maps are linear).
  std::vector<SurfaceAnchors> to_finest;
  /// Per input vertex: its group (a handle: vertices held or moved together), −1 if free.
  /// Groups survive decimation: a collapse never merges two groups and passes the group of
  /// its removed vertex to the kept one (level_groups()).
  std::vector<int> input_group;
  /// Every collapse, in decimation order (fine to coarse).
  std::vector<CollapseRecord> collapses;
  /// first_collapse[l]: index in `collapses` of the first collapse that leaves level l
  /// (size L + 1; first_collapse[L] = 0). Collapses [first_collapse[l+1], first_collapse[l])
  /// turn level l+1 into level l.
  std::vector<int> first_collapse;
  /// expansion_batches[l] (l < L): the vertex splits refining level l into l+1, as indices
  /// into `collapses`, grouped in batches that can run in parallel, to be applied in order
  /// (PSQ §4.4.4, Algorithms 6–7).
  std::vector<std::vector<std::vector<int>>> expansion_batches;

  int num_levels() const { return static_cast<int>(levels.size()); }
  int finest() const { return num_levels() - 1; }
};

/// Per vertex of level `level`, its group (−1 free): input_group carried through the collapses
/// that lead to the level.
std::vector<int> level_groups(const MeshHierarchy& hierarchy, int level);

/// Per input vertex, its index on level `level` (−1 where the level does not have it): the
/// inverse of levels[level].input_vertex.
std::vector<int> level_vertex_index(const MeshHierarchy& hierarchy, int level);

/// The faces of a level as input-mesh vertex id triples (the ids collapse records use).
std::vector<FaceCorners> level_input_faces(const HierarchyLevel& level);

/// How to build a hierarchy.
struct HierarchyOptions {
  /// Vertex counts of the levels below the user's mesh, any order, each distinct and below
  /// its vertex count. Empty: a single-level hierarchy.
  std::vector<int> coarse_vertex_counts;
  /// Empty, or per input vertex its group (−1 free, else ≥ 0; e.g. the handle it belongs to).
  /// Vertices of a group keep their rest positions on every level where they survive, every
  /// group keeps at least one vertex, and no collapse joins two groups.
  std::vector<int> vertex_groups;
  /// Every coarse vertex keeps the rest position of the input vertex it is (each collapse keeps
  /// the endpoint nearer the quadric optimum), so the coarse levels of a convex surface lie
  /// inside it. For progressive obstacles, whose coarse copies must not bulge into a shell
  /// resting on them.
  bool keep_input_positions = false;
  /// Empty, or per input vertex its contact offset ξ_v (m, e.g. half the shell thickness): no
  /// collapse then brings two primitives that contact pairs (a vertex and a face, two edges,
  /// sharing no vertex) within the sum of their offsets. No collapse ever makes faces cross.
  std::vector<double> contact_offsets;
};

/// Level sizes shrinking by a constant factor: round(n / ratio^k) for k = count … 1, coarsest
/// first (the PSQ examples use about ×4 per level). Throws Error(invalid_argument) unless
/// ratio > 1, count ≥ 1 and the coarsest size is at least 4.
std::vector<int> geometric_level_counts(int finest_vertices, double ratio, int count);

/// Progress report during a long build: fraction done in [0, 1] and a phase name. Returning
/// false cancels (Error(cancelled)).
using HierarchyProgress = bool (*)(void* user, double fraction, const char* phase);

/// Builds the hierarchy of `mesh` (which must pass validate_mesh): decimation with
/// probabilistic quadrics tracking the intrinsic map, then expansion coloring. Throws
/// Error(invalid_mesh) for a mesh that fails validation or cannot be decimated that far,
/// Error(invalid_argument) for bad vertex counts, Error(cancelled) if progress says stop.
MeshHierarchy build_hierarchy(const TriangleMesh& mesh, const HierarchyOptions& options,
                              HierarchyProgress progress = nullptr, void* user = nullptr);

/// Checks the shape of a hierarchy read from elsewhere: level sizes, anchors in range with
/// valid weights, record ids in range, batches covering each level's collapses exactly once.
/// Throws Error(invalid_argument) naming the first violation.
void check_hierarchy_structure(const MeshHierarchy& hierarchy);

/// check_hierarchy_structure(), then that every level is a valid mesh (Error(invalid_mesh)
/// from validate_mesh), that the batches are exactly those expansion_batches() computes from
/// the records, and that applying them turns each level into the next (Error(invalid_argument)
/// otherwise).
void check_hierarchy(const MeshHierarchy& hierarchy);

}  // namespace progsim
