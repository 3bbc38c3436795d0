#pragma once
/// @file Scheduling of the vertex splits that refine one hierarchy level into the next: greedy
/// coloring on the dynamically expanding mesh, so that each batch of splits can be expanded in
/// parallel (PSQ §4.4.4, Algorithms 6–7).
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"

namespace progsim {

/// Groups the vertex splits that refine a coarse level into the next finer one into batches that
/// can be expanded in parallel (PSQ §4.4.4, Algorithms 6–7). `coarse_faces`: the faces of the
/// coarse level as input-vertex-id triples; `collapses`: all records; the splits to schedule are
/// the records [first, last) (the collapses that turned the fine level into the coarse one, in
/// decimation order). Returns batches of record indices (absolute indices into `collapses`), to
/// be applied in order. Within a batch the sets R = closed one-ring of `kept` in the current mesh
/// ∪ vertices of `before` are pairwise disjoint (Algorithm 7), so no two `kept` vertices are
/// combinatorial neighbours or share a neighbour. A split is scheduled only after every later
/// collapse that touched its faces: one that destroyed one of its `after` faces, or one whose
/// `after` lists a face this collapse created (undoing this one first would remove that face for
/// good). Throws Error(invalid_argument) if [first, last) is not a range of `collapses`, and
/// Error(internal) if the records are inconsistent with `coarse_faces` (a negative vertex id, a
/// face created by two collapses, or a split that never becomes ready).
std::vector<std::vector<int>> expansion_batches(const std::vector<FaceCorners>& coarse_faces,
                                                const std::vector<CollapseRecord>& collapses,
                                                int first, int last);

/// Applies the vertex splits of `batch` to a face set (PSQ §4.4.4): erases the `after` faces of
/// all its records, then inserts their `before` faces (the splits of a batch of
/// expansion_batches touch disjoint faces; replay a sequence one split per call). Faces are
/// matched up to cyclic rotation of their corners; on return `faces` holds every face rotated so
/// that its smallest corner comes first, sorted (such input is not re-sorted, so a replay costs
/// O(|faces|) per batch). For replaying a schedule (the refinement applies batches this way).
/// Throws Error(invalid_argument) for a record index outside `collapses`, Error(internal) if an
/// `after` face is missing.
void apply_splits(std::vector<FaceCorners>& faces, const std::vector<CollapseRecord>& collapses,
                  const std::vector<int>& batch);

/// True if two face lists hold the same oriented faces as multisets, each face up to cyclic
/// rotation of its corners (a reversed face differs). Compares mesh states of the expansion
/// (PSQ §4.4.4).
bool same_faces(std::vector<FaceCorners> a, std::vector<FaceCorners> b);

}  // namespace progsim
