#include "solve/sparse_cholesky.hpp"

#include <omp.h>

#include <Eigen/CholmodSupport>
#include <string>

#include "common/error.hpp"
#include "solve/blas_threads.hpp"

namespace progsim {

struct SparseCholesky::Impl {
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt;
  bool analyzed = false;
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {
  impl_->llt.cholmod().print = 0;  // CHOLMOD must not write to stdout/stderr: we report.
}

SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const SparseMatrix& h) {
  impl_->llt.analyzePattern(h);
  impl_->analyzed = true;
}

namespace {

/// The threads CHOLMOD runs on, for the lifetime of the object (factorization and solves).
/// CHOLMOD's supernodal numeric factorization opens OpenMP regions with a fixed team size
/// (CHOLMOD_OMP_NUM_THREADS = 4 in SuiteSparse 5) whatever the machine. On fewer cores,
/// alternating with our own regions makes libgomp create and destroy threads on every
/// factorization (measured: 960 thread creations and 3.8 s of 5 s in a 642-vertex balloon
/// run). With dynamic adjustment the runtime sizes CHOLMOD's teams to the cores available.
/// The dense kernels CHOLMOD calls (dpotrf, dsyrk, dgemm; dtrsv in solves) must then run on
/// `blas_threads`, 1 unless asked: OpenBLAS's OpenMP build sizes its team from
/// omp_get_max_threads() and its first thread waits for every member, so when dynamic
/// adjustment starts fewer under load it spins in sched_yield forever (seen: tests hung for
/// over 10 min under dpotrf when two ran at once on 2 cores); its pthreads build takes the
/// count from ScopedBlasThreads. Either way the result then does not depend on the process's
/// thread settings (tests/blas/blas_variants.cpp).
class CholmodThreads {
 public:
  explicit CholmodThreads(int blas_threads)
      : blas_(blas_threads), was_dynamic_(omp_get_dynamic()), threads_(omp_get_max_threads()) {
    omp_set_dynamic(1);
    omp_set_num_threads(1);  // BLAS calls from this thread: no team
  }
  ~CholmodThreads() {
    omp_set_num_threads(threads_);
    omp_set_dynamic(was_dynamic_);
  }
  CholmodThreads(const CholmodThreads&) = delete;
  CholmodThreads& operator=(const CholmodThreads&) = delete;

 private:
  ScopedBlasThreads blas_;
  int was_dynamic_, threads_;
};

}  // namespace

bool SparseCholesky::factorize(const SparseMatrix& h, bool allow_shift) {
  if (!impl_->analyzed) analyze(h);
  const int max_retries = allow_shift ? 8 : 0;
  const double scale = std::max(h.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  double shift = 0.0;
  for (int attempt = 0; attempt <= max_retries; ++attempt) {
    impl_->llt.setShift(shift);
    {
      const CholmodThreads threads(blas_threads_);
      impl_->llt.factorize(h);
    }
    if (impl_->llt.info() == Eigen::Success) {
      shift_ = shift;
      return true;
    }
    shift = shift == 0.0 ? 1e-10 * scale : shift * 100.0;
  }
  return false;
}

void SparseCholesky::solve(const Vector& b, Vector& x) const {
  {
    const CholmodThreads threads(blas_threads_);
    x = impl_->llt.solve(b);
  }
  if (impl_->llt.info() != Eigen::Success)
    fail(Status::numerical_failure, "CHOLMOD triangular solve failed");
}

void SparseCholesky::set_blas_threads(int threads) {
  if (threads < 1)
    fail(Status::invalid_argument,
         "BLAS thread count " + std::to_string(threads) + " must be at least 1");
  blas_threads_ = threads;
}

double SparseCholesky::factorization_flops() const {
  return impl_->llt.cholmod().fl;
}

}  // namespace progsim
