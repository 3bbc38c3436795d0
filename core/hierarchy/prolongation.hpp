#pragma once
/// @file The interface of a prolongation operator x_fine = P(x_coarse) between two levels of a
/// hierarchy, P(x) = U x + a(x) (PSQ eqs. 7 and 9). U is the sparse intrinsic (barycentric) part,
/// a(x) the per-vertex offsets; a linear prolongation has a ≡ 0.
#include <Eigen/SparseCore>
#include <utility>

#include "common/types.hpp"
#include "hierarchy/surface_anchor.hpp"

namespace progsim {

/// Row-major sparse matrix acting on positions: (n_fine × n_coarse), ≤ 3 entries per row.
using ProlongationMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// A map from coarse positions to fine positions. Implementations are immutable after
/// construction, so one operator may be applied from several threads at once.
class Prolongation {
 public:
  virtual ~Prolongation() = default;
  Prolongation(const Prolongation&) = default;
  Prolongation(Prolongation&&) noexcept = default;
  Prolongation& operator=(const Prolongation&) = default;
  Prolongation& operator=(Prolongation&&) noexcept = default;

  /// Vertices of the coarse (input) and fine (output) level.
  int coarse_vertices() const { return static_cast<int>(intrinsic_.cols()); }
  int fine_vertices() const { return static_cast<int>(intrinsic_.rows()); }

  /// The intrinsic part U (n_fine × n_coarse, ≤ 3 entries per row, rows summing to 1): fine
  /// vertex i = Σ_j U_ij x_j + a_i (PSQ eq. 7).
  const ProlongationMatrix& intrinsic() const { return intrinsic_; }

  /// a(x): per fine vertex, the offset added to U x (n_fine × 3). Zero for linear operators.
  /// `out` must already have n_fine rows (no allocation). Throws Error(invalid_argument) on a
  /// shape mismatch.
  virtual void offsets(const Positions& coarse, Positions& out) const = 0;

  /// P(x) = U x + a(x) into `fine` (n_fine × 3, already sized: no allocation).
  /// OpenMP-parallel over fine vertices. Throws Error(invalid_argument) on a shape mismatch.
  virtual void apply(const Positions& coarse, Positions& fine) const = 0;

  /// Convenience: P(x) as a new array.
  Positions operator()(const Positions& coarse) const {
    Positions fine(fine_vertices(), 3);
    apply(coarse, fine);
    return fine;
  }

  /// Uᵀ g: a fine-level per-vertex gradient (n_fine × 3) restricted to the coarse level
  /// (n_coarse × 3), as in the proxy gradient (U^l)ᵀ ∇Ψ_L (PSQ §4.5, eq. 10, with a frozen offset).
  Positions restrict_gradient(const Positions& fine_gradient) const;

 protected:
  explicit Prolongation(ProlongationMatrix intrinsic) : intrinsic_(std::move(intrinsic)) {}

  /// Throws Error(invalid_argument), naming `operation`, unless `coarse` has coarse_vertices()
  /// rows, `out` has fine_vertices() rows, and the two are distinct arrays.
  void check_shapes(const Positions& coarse, const Positions& out, const char* operation) const;

  /// Row i of U x (3): the intrinsic anchor v_i = Σ_j U_ij x_j of fine vertex i (PSQ eq. 7).
  Vec3 intrinsic_point(const Positions& coarse, Eigen::Index i) const;

 private:
  ProlongationMatrix intrinsic_;
};

/// U (n_fine × coarse_vertices, n_fine = anchors.size()): row i holds the barycentric weights of
/// anchor i at the corners of its coarse face, exact zeros left out (PSQ eq. 7, U^l_{l+1}).
/// Throws Error(invalid_argument) naming the fine vertex if an anchor's face is out of range or
/// its weights are non-finite, below −1e-9 or do not sum to 1 ± 1e-9; Error(invalid_mesh)
/// naming the face if a coarse face has a corner outside [0, coarse_vertices).
ProlongationMatrix intrinsic_matrix(const SurfaceAnchors& anchors, const Faces& coarse_faces,
                                    int coarse_vertices);

}  // namespace progsim
