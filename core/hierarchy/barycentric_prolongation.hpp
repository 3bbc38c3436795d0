#pragma once
/// @file Linear (intrinsic-only) prolongation P(x) = U x (PSQ eq. 7 with a ≡ 0; intrinsic
/// prolongation of Liu et al. 2021): every fine vertex follows its barycentric anchor. Meant for
/// volumetric levels and as the baseline the shell prolongation is compared against.
#include "hierarchy/prolongation.hpp"
#include "hierarchy/surface_anchor.hpp"

namespace progsim {

/// P(x) = U x with U built from one SurfaceAnchor per fine vertex; offsets are zero.
class BarycentricProlongation final : public Prolongation {
 public:
  /// `coarse_faces` (|F_c| × 3) index `coarse_vertices` coarse vertices; `anchors` has one entry
  /// per fine vertex. Throws as intrinsic_matrix() does.
  BarycentricProlongation(const Faces& coarse_faces, int coarse_vertices,
                          const SurfaceAnchors& anchors);

  /// Sets `out` (n_fine × 3) to zero after checking the shapes.
  void offsets(const Positions& coarse, Positions& out) const override;

  /// fine = U coarse (n_fine × 3), OpenMP-parallel over fine vertices, no allocation.
  void apply(const Positions& coarse, Positions& fine) const override;
};

}  // namespace progsim
