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
class GalerkinHessian {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /// `finest` must outlive this object; `at` (3 n_L) is any finest state, used to fix the
  /// pattern. Throws Error(invalid_argument) on mismatched sizes.
  GalerkinHessian(const ProlongationMatrix& intrinsic, Problem& finest, const Vector& at);

  /// Entries of the coarse matrix (3 n_l × 3 n_l, both triangles).
  std::size_t entry_count() const { return static_cast<std::size_t>(pattern_.nonZeros()); }
  /// Row and column of every entry, in the order values() writes them.
  void pattern(int* rows, int* cols) const;
  /// The entries at the finest state `fine_x`; finest vertices in `pinned` do not depend on the
  /// coarse state (their rows and columns of H are left out).
  void values(const Vector& fine_x, bool project_psd, const std::vector<int>& pinned, double* out);

 private:
  /// Uᵀ M H M U, M the diagonal mask of the free finest DOFs.
  SparseMatrix product(const Vector& fine_x, bool project_psd, const std::vector<int>& pinned);

  Problem& finest_;
  SparseMatrix lift_;     // U ⊗ I₃ (3 n_L × 3 n_l)
  SparseMatrix pattern_;  // structure of Uᵀ H U
  Eigen::VectorXd mask_;  // 1 for free finest DOFs, 0 for pinned ones
};

}  // namespace progsim
