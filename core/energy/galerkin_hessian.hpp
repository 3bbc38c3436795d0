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
/// construction, and so is how each coarse entry gathers the finest Hessian's entries: an
/// evaluation is a numeric sparse triple product over that structure (Gustavson's column
/// algorithm, one coarse column per task, OpenMP-parallel and deterministic), with no allocation
/// once every thread has its workspace. Why not Eigen's sparse products: they rebuild the
/// pattern, sort and allocate each time (measured on the 34K-vertex drape's 30-step preview:
/// 68.4 s with them, 39.6 s with this, the same Newton iterations).
///
/// Lazy refresh: the matrix only preconditions the proxy (its gradient stays exact), so an
/// evaluation reuses the last one while the finest state has moved, net of its mean
/// translation (to which elastic energies are blind), by at most `refresh_distance` at every
/// vertex since then (a modified Newton method: Kelley 2003, "Solving nonlinear equations with
/// Newton's method", §2.3 "The chord and Shamanskii methods"). 0: every evaluation assembles.
class GalerkinHessian {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /// `finest` must outlive this object; `at` (3 n_L) is any finest state, used to read the
  /// finest Hessian's pattern; `refresh_distance` (m, ≥ 0) as above. Throws
  /// Error(invalid_argument) on mismatched sizes or a negative distance.
  GalerkinHessian(const ProlongationMatrix& intrinsic, Problem& finest, const Vector& at,
                  double refresh_distance = 0.0);

  /// Entries of the coarse matrix (3 n_l × 3 n_l, both triangles).
  std::size_t entry_count() const { return coarse_rows_.size(); }
  /// Row and column of every entry, in the order values() writes them (by column, rows
  /// ascending).
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
  /// A thread's accumulators for one coarse column: H U's column over the finest DOFs (with
  /// the DOFs it touched, stamped by column) and Uᵀ H U's column over the coarse DOFs.
  struct Workspace {
    std::vector<double> fine;
    std::vector<int> stamp, touched;
    std::vector<double> coarse;
  };

  /// The symmetric finest pattern by columns from the lower triangle the problem stores.
  void index_full_hessian(const SparseMatrix& lower);
  /// The coarse pattern: the coarse DOFs that reach coarse DOF `column` through H and U.
  void build_pattern();
  /// Every finest DOF touched from coarse DOF `column` through U then H, stamped in `w`.
  void touch_column(int column, const double* h, Workspace& w) const;
  /// Column `column` of (MU)ᵀ H (MU) from the finest Hessian's lower entries `h`, into `out`.
  void coarse_column(int column, const double* h, Workspace& w, double* out) const;
  /// Uᵀ M H M U's entries into `out`, M the diagonal mask of the free finest DOFs.
  void assemble(const Vector& fine_x, bool project_psd, const std::vector<int>& pinned,
                double* out);
  /// True when the last assembly can stand for the matrix at `fine_x`.
  bool reusable(const Vector& fine_x, bool project_psd, const std::vector<int>& pinned) const;

  Problem& finest_;
  long finest_pattern_version_;
  SparseMatrix lift_;                                            // U ⊗ I₃, by coarse DOF
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> lift_rows_;  // the same, by finest DOF
  // H's both triangles by column: rows, and the index of each entry among the stored lower ones.
  std::vector<int> full_start_, full_rows_, full_entries_;
  std::vector<int> coarse_start_, coarse_rows_;  // the coarse pattern (CSC)
  std::vector<double> mask_;                     // 1 on free finest DOFs, 0 on pinned ones
  std::vector<int> masked_pinned_;
  std::vector<Workspace> workspaces_;  // one per OpenMP thread
  double refresh_distance_;
  // The last assembly: its entries, and the state, projection and pinned set it was made at.
  std::vector<double> last_values_;
  Vector last_x_;
  bool last_projected_ = false;
  std::vector<int> last_pinned_;
  long assemblies_ = 0, reuses_ = 0;
};

}  // namespace progsim
