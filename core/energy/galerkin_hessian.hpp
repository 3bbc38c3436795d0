#pragma once
/// @file The Galerkin (Ritz) projection of the finest level's shell Hessian onto a coarse
/// level: Uᵀ ∇²Ψ_L U, the Newton matrix of x ↦ Ψ_L(U x + a) with the offsets a frozen (the
/// matrix of PSQ eq. 10's frozen-offset system). A stronger preconditioner for the proxy than
/// the level's own Hessian, at the price of a finest-level Hessian assembly per iteration.
#include <Eigen/SparseCore>
#include <vector>

#include "hierarchy/prolongation.hpp"
#include "problem/problem.hpp"

namespace progsim {

/// Uᵀ H U with H = the Hessian of a finest-level Problem (3 n_L DOFs, no fixed DOFs,
/// finalized) and U = `intrinsic` ⊗ I₃ (n_L × n_l blocks). The pattern is fixed at
/// construction. Allocates per evaluation (sparse products): not for allocation-free paths.
///
/// Lazy refresh: the matrix only preconditions the proxy (its gradient stays exact), so an
/// evaluation reuses the last one while the finest state has moved, net of its mean
/// translation (to which elastic energies are blind), by at most `refresh_distance` at every
/// vertex since then (a modified Newton method: Kelley 2003, "Solving nonlinear equations with
/// Newton's method", §2.3 "The chord and Shamanskii methods"). 0: every evaluation assembles.
class GalerkinHessian {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /// `finest` must outlive this object; `at` (3 n_L) is any finest state, used to fix the
  /// pattern; `refresh_distance` (m, ≥ 0) as above. Throws Error(invalid_argument) on
  /// mismatched sizes or a negative distance.
  GalerkinHessian(const ProlongationMatrix& intrinsic, Problem& finest, const Vector& at,
                  double refresh_distance = 0.0);

  /// Entries of the coarse matrix (3 n_l × 3 n_l, both triangles).
  std::size_t entry_count() const { return static_cast<std::size_t>(pattern_.nonZeros()); }
  /// Row and column of every entry, in the order values() writes them.
  void pattern(int* rows, int* cols) const;
  /// The entries at the finest state `fine_x` (or those of an earlier state within the refresh
  /// distance, with the same `project_psd` and `pinned`); finest DOFs in `pinned` (3v + k) do
  /// not depend on the coarse state (their rows and columns of H are left out).
  void values(const Vector& fine_x, bool project_psd, const std::vector<int>& pinned, double* out);

  /// The next values() assembles, whatever the distance moved.
  void refresh() { last_x_.resize(0); }

  /// Evaluations that assembled the finest Hessian, and those that reused an earlier one.
  long assemblies() const { return assemblies_; }
  long reuses() const { return reuses_; }

 private:
  /// True when the last assembly can stand for the matrix at `fine_x`.
  bool reusable(const Vector& fine_x, bool project_psd, const std::vector<int>& pinned) const;
  /// Uᵀ M H M U, M the diagonal mask of the free finest DOFs.
  SparseMatrix product(const Vector& fine_x, bool project_psd, const std::vector<int>& pinned);

  Problem& finest_;
  SparseMatrix lift_;     // U ⊗ I₃ (3 n_L × 3 n_l)
  SparseMatrix pattern_;  // structure of Uᵀ H U
  // M U and its transpose (M: 1 on free finest DOFs, 0 on the pinned DOFs masked_pinned_).
  SparseMatrix masked_lift_, masked_lift_transpose_;
  std::vector<int> masked_pinned_;
  double refresh_distance_;
  // The last assembly: its entries, and the state, projection and pinned set it was made at.
  std::vector<double> last_values_;
  Vector last_x_;
  bool last_projected_ = false;
  std::vector<int> last_pinned_;
  long assemblies_ = 0, reuses_ = 0;
};

}  // namespace progsim
