#pragma once
/// @file The thread count of the dense BLAS/LAPACK kernels CHOLMOD's supernodal factorization
/// calls (dpotrf, dtrsm, dsyrk, dgemm), where most of a large factorization's time goes
/// (issue 33 §5). Which BLAS runs is the system's choice (Debian's libblas.so.3 alternative),
/// so this works through whatever is loaded: OpenBLAS built with pthreads gets the count for
/// the scope; any other BLAS is left as it is.

namespace progsim {

/// How the loaded BLAS runs in parallel.
enum class BlasThreading {
  unknown,   ///< not OpenBLAS (reference BLAS, MKL, Accelerate...): left alone
  serial,    ///< OpenBLAS built without threads
  pthreads,  ///< OpenBLAS with its own thread pool: the count can be set per scope
  openmp,    ///< OpenBLAS on OpenMP: runs on the calling thread's OpenMP team
};

/// The threading of the BLAS this process has loaded (found once, by its exported symbols).
BlasThreading loaded_blas_threading();

/// Sets the loaded OpenBLAS's pthread pool to `threads` for the object's lifetime and restores
/// the previous count after. The pool is one per process: while scopes overlap (factorizations
/// on several threads) the first one's count holds until the last one ends. Does nothing for
/// any other BLAS (see BlasThreading): OpenBLAS on OpenMP follows the calling thread's
/// omp_set_num_threads(), the others their own settings.
class ScopedBlasThreads {
 public:
  explicit ScopedBlasThreads(int threads);
  ~ScopedBlasThreads();
  ScopedBlasThreads(const ScopedBlasThreads&) = delete;
  ScopedBlasThreads& operator=(const ScopedBlasThreads&) = delete;

 private:
  bool counted_ = false;  // this scope is one of the open ones
};

}  // namespace progsim
