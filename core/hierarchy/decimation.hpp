#pragma once
/// @file Fine-to-coarse decimation of a triangle mesh by quadric edge collapse with
/// probabilistic quadrics (CGAL Surface_mesh_simplification; PSQ §4.1, Trettner and Kobbelt
/// 2020), tracking where every finer vertex lands on each coarser level through joint
/// flattenings of each collapse (the intrinsic map of PSQ §4.3, after Liu et al. 2021).
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"

namespace progsim {

/// Decimates `mesh` (validated by the caller) through options.coarse_vertex_counts (distinct,
/// each at least 4 and below |V|, any order), keeping the vertex groups (empty: none) and, if
/// asked, the input positions. Fills every field of the result except expansion_batches.
/// Throws Error(invalid_argument) for counts out of range or malformed groups,
/// Error(invalid_mesh) when no further collapse keeps the surface valid before a count is
/// reached, Error(cancelled) when `progress` returns false.
MeshHierarchy decimate(const TriangleMesh& mesh, const HierarchyOptions& options,
                       HierarchyProgress progress, void* user);

}  // namespace progsim
