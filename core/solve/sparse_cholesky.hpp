#pragma once
/// @file Sparse Cholesky factorization through CHOLMOD (supernodal), with the symbolic
/// analysis done once per sparsity pattern and a diagonal shift retried on failure.
#include <Eigen/SparseCore>
#include <memory>

#include "common/types.hpp"

namespace progsim {

/// Solves H p = b for symmetric H (lower triangle stored). Wraps Eigen's CHOLMOD binding.
class SparseCholesky {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// Symbolic analysis (fill-reducing ordering, supernodes) for H's pattern. Call again when
  /// the pattern changes.
  void analyze(const SparseMatrix& h);

  /// Numeric factorization of H + σI. Tries σ = 0 first; if H is not positive definite and
  /// allow_shift is set, retries with σ growing from 1e-10·max|diag(H)| by ×100 (at most 8
  /// retries). @return false if every attempt failed. shift() reports the σ that succeeded.
  bool factorize(const SparseMatrix& h, bool allow_shift = true);

  /// x = (H + σI)⁻¹ b, with σ = shift(). Precondition: factorize() returned true.
  void solve(const Vector& b, Vector& x) const;

  /// The diagonal shift σ of the last successful factorization (0 when none was needed).
  double shift() const { return shift_; }

  /// Threads of the dense kernels (dpotrf, dsyrk, dgemm) in factorize() and solve(), where the
  /// BLAS has a thread pool of its own (OpenBLAS built with pthreads; solve/blas_threads.hpp).
  /// Default 1, whatever BLAS the system chose: results then do not depend on the thread count
  /// and do not collapse when another process holds a core (bench_cholmod_threads measures
  /// both). Throws Error(invalid_argument) below 1.
  void set_blas_threads(int threads);

  /// CHOLMOD's floating-point operation count of one factorization of the analysed pattern.
  double factorization_flops() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double shift_ = 0.0;
  int blas_threads_ = 1;
};

}  // namespace progsim
