#pragma once
/// @file Shell prolongation P(x) = U x + a(x) (PSQ §4.3, eqs. 4–9): each fine vertex follows
/// its intrinsic anchor on a coarse face plus a rest offset that rotates with that face, so
/// rest shapes are recovered exactly and bending of the coarse shell carries the fine detail.
#include <vector>

#include "common/types.hpp"
#include "hierarchy/prolongation.hpp"
#include "hierarchy/surface_anchor.hpp"

namespace progsim {

/// P(x) = U x + a(x) with a_i(x) = n(x) γ_i + R(F(x)) t_i (PSQ eqs. 5 and 7). Serves both the
/// per-level operator P^l_{l+1} and the direct one P^l (eq. 9): only the anchors and the fine
/// rest positions differ. Immutable: apply() and offsets() are const, thread-safe and
/// allocation-free (the face frame is recomputed per fine vertex, nothing is cached).
class ShellProlongation final : public Prolongation {
 public:
  /// Coarse rest mesh `coarse_rest` (|V_c| × 3) and `coarse_faces` (|F_c| × 3); `anchors`, one
  /// per fine vertex, on coarse faces; `fine_rest` (n_fine × 3). Stores per fine vertex the rest
  /// offset d̄ = x̄_i − v̄_i (v̄ = U x̄_c) in its face's rest frame: γ = n̄ᵀ d̄ and
  /// t = (ēᵀ d̄, (n̄ × ē)ᵀ d̄) (PSQ §4.3 before eq. 4). Throws Error(invalid_argument) on an
  /// anchor count that differs from fine_rest.rows(), non-finite fine rest positions or a bad
  /// anchor (see intrinsic_matrix()); Error(invalid_mesh) naming the face if a coarse face has a
  /// corner out of range or is degenerate (zero or non-finite area) at rest.
  ShellProlongation(const Positions& coarse_rest, const Faces& coarse_faces,
                    const SurfaceAnchors& anchors, const Positions& fine_rest);

  /// a(x) (n_fine × 3), PSQ eqs. 5–6/8. Invariant under uniform scaling of x, equivariant
  /// under rotations. A fine vertex whose coarse face is degenerate in x (zero or non-finite
  /// area, so n and R are undefined) gets a_i = 0, i.e. it falls back to its anchor U x.
  void offsets(const Positions& coarse, Positions& out) const override;

  /// coarse_gradient += J(x)ᵀ fine_gradient with J = ∂P/∂x = U + ∂a/∂x, the exact chain rule
  /// of a fine-level gradient through the prolongation (PSQ eq. 10 uses Uᵀ only, freezing a).
  /// Shapes: coarse (n_coarse × 3), fine_gradient (n_fine × 3), coarse_gradient (n_coarse × 3).
  /// OpenMP-parallel, the same result for any thread count, and allocation-free once
  /// `workspace` (per coarse face, 9 values; reuse it across calls) has been sized.
  void add_jacobian_transpose(const Positions& coarse, const Positions& fine_gradient,
                              Positions& coarse_gradient,
                              std::vector<Eigen::Matrix<double, 9, 1>>& workspace) const;

  /// fine = U x + a(x) (n_fine × 3), PSQ eqs. 4, 7, 9; OpenMP-parallel over fine vertices.
  void apply(const Positions& coarse, Positions& fine) const override;

 private:
  /// The frame [R(F) | n] (3 × 3) of coarse face f at positions x (PSQ eq. 5, footnote 2);
  /// false if the face has zero or non-finite area there.
  bool frame_of(const Positions& x, int f, Mat3& frame) const;
  /// The lists add_jacobian_transpose gathers by (built once).
  void build_gather_lists(int coarse_vertices);
  /// a_i(x) (3) of fine vertex i (PSQ eq. 5).
  Vec3 offset(const Positions& coarse, Eigen::Index i) const;

  Faces coarse_faces_;                      ///< (|F_c| × 3)
  std::vector<Mat2> face_rest_inverse_;     ///< per coarse face: D̄⁻¹ (2 × 2), F = D D̄⁻¹
  std::vector<int> anchor_face_;            ///< per fine vertex: its coarse face
  std::vector<Vec3> local_offset_;          ///< per fine vertex: (t₁, t₂, γ)
  ProlongationMatrix intrinsic_transpose_;  ///< Uᵀ (n_coarse × n_fine), to gather Uᵀg by rows
  std::vector<int> face_fine_first_;        ///< (|F_c| + 1): fine vertices of face f are
  std::vector<int> face_fine_;              ///< face_fine_[first[f], first[f + 1])
  std::vector<int> vertex_corner_first_;    ///< (n_coarse + 1): corners of coarse vertex v,
  std::vector<int> vertex_corner_;          ///< as 3·face + corner, in increasing order
};

}  // namespace progsim
