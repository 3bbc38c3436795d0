#pragma once
/// @file A hierarchy of non-conforming tet meshes of one solid (VPD §3.1.2): the boundary of the
/// user's tet mesh decimated into coarser surfaces, each tetrahedralized anew, and the
/// prolongation between neighbouring levels from binding each finer vertex to a coarser tet
/// (VPD §3.3). No correspondences are tracked through the decimation.
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"
#include "hierarchy/prolongation.hpp"
#include "hierarchy/tet_binding.hpp"
#include "mesh/tet_mesh.hpp"
#include "mesh/tetrahedralize.hpp"

namespace progsim {

/// Levels 0 (coarsest) … L (the user's mesh) with the prolongations between them.
struct TetHierarchy {
  std::vector<TetMesh> levels;  ///< 0 = coarsest; levels.back() is the input, unchanged
  /// to_finer[l] (l < L): W_l (|V_{l+1}| × |V_l|), level l+1's vertices as barycentric
  /// combinations (negative outside) of level l's tets' corners; rows sum to 1.
  std::vector<ProlongationMatrix> to_finer;
  /// bindings[l] (l < L): per vertex of level l+1, its tet of level l and weights (W_l's rows).
  std::vector<std::vector<TetBinding>> bindings;

  int num_levels() const { return static_cast<int>(levels.size()); }
  /// Positions `x` of level `level` carried to the finest level, W_{L−1} ⋯ W_level x (VPD §3.3).
  Positions prolong_to_finest(int level, Positions x) const {
    for (int l = level; l + 1 < num_levels(); ++l) x = to_finer[l] * x;
    return x;
  }
};

/// How to build a tet hierarchy.
struct TetHierarchyOptions {
  /// Boundary vertex counts of the decimated surfaces S_0 … S_{L−1}, any order, distinct, each
  /// at least 4 and below the input boundary's vertex count. Empty: a single level. The tet
  /// levels' vertex counts follow from the tetrahedralization (interior vertices added, the
  /// surface resampled).
  std::vector<int> coarse_boundary_vertex_counts;
  /// Decimation keeps input vertex positions (HierarchyOptions::keep_input_positions): flat
  /// faces, sharp edges and corners of S_L then stay exactly where they are on every level (a
  /// box stays the same box), at the price of coarse levels lying inside convex parts. Off, the
  /// quadric optimum moves corners by a fraction of the local edge length, and the finer
  /// level's corner vertices then bind to small coarse tets near the moved corner with large
  /// extrapolation weights (|w| up to 11 measured on a box).
  bool keep_input_positions = false;
  /// Level l is tetrahedralized with cell_size, facet_size and edge_size equal to size_factor
  /// times the mean edge length of S_l (m), facet_distance a tenth of that. 0.6 gives tets
  /// with edges about as long as S_l's (a regular tet's circumradius is 0.61 of its edge).
  double size_factor = 0.6;
  /// The other bounds (facet_angle, cell_radius_edge_ratio, feature_angle, seed); its sizes
  /// (cell_size, facet_size, facet_distance, edge_size) are ignored, set per level as above.
  TetrahedralizeOptions tetrahedralize;
};

/// Builds the hierarchy of `finest` (VPD §3.1.2): extracts its boundary S_L, decimates it
/// (Garland–Heckbert with probabilistic quadrics, decimation.hpp, which keeps each level free of
/// self-intersections) to the requested boundary vertex counts, tetrahedralizes each S_l
/// (tetrahedralize_surface, CGAL Mesh_3), and binds each level's vertices to the next coarser
/// level's tets (bind_to_tets, VPD §3.3.3) for W_l. Deterministic. `progress` (may be null) is
/// called with the fraction done and the phase ("decimation", "tetrahedralization",
/// "binding"); returning false cancels.
/// Throws Error(invalid_mesh) if `finest` fails validate_tet_mesh, a count cannot be reached by
/// decimation or a level's tetrahedralization fails validation; Error(invalid_argument) for
/// counts out of range or repeated, or size_factor not positive and finite, or another
/// tetrahedralization option out of range; Error(cancelled) if progress says stop.
TetHierarchy build_tet_hierarchy(const TetMesh& finest, const TetHierarchyOptions& options,
                                 HierarchyProgress progress = nullptr, void* user = nullptr);

}  // namespace progsim
