#include "solve/sparse_cholesky.hpp"

#include <omp.h>

#include <Eigen/CholmodSupport>

#include "common/error.hpp"

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

/// CHOLMOD's supernodal numeric factorization opens OpenMP regions with a fixed team size
/// (CHOLMOD_OMP_NUM_THREADS = 4 in SuiteSparse 5) whatever the machine. On fewer cores,
/// alternating with our own regions makes libgomp create and destroy threads on every
/// factorization (measured: 960 thread creations and 3.8 s of 5 s in a 642-vertex balloon
/// run). With dynamic adjustment the runtime sizes CHOLMOD's teams to the cores available.
/// The dense kernels CHOLMOD calls (dpotrf, dsyrk) must then run single-threaded: OpenBLAS's
/// OpenMP build sizes its team from omp_get_max_threads() and its first thread waits for every
/// member, so when dynamic adjustment starts fewer under load it spins in sched_yield forever
/// (seen: tests hung for over 10 min under dpotrf when two ran at once on 2 cores).
template <typename Factorization>
void factorize_with_dynamic_threads(Factorization& llt, const SparseCholesky::SparseMatrix& h) {
  const int was_dynamic = omp_get_dynamic();
  const int threads = omp_get_max_threads();
  omp_set_dynamic(1);
  omp_set_num_threads(1);  // BLAS calls from this thread: no team
  llt.factorize(h);
  omp_set_num_threads(threads);
  omp_set_dynamic(was_dynamic);
}

}  // namespace

bool SparseCholesky::factorize(const SparseMatrix& h, bool allow_shift) {
  if (!impl_->analyzed) analyze(h);
  const int max_retries = allow_shift ? 8 : 0;
  const double scale = std::max(h.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  double shift = 0.0;
  for (int attempt = 0; attempt <= max_retries; ++attempt) {
    impl_->llt.setShift(shift);
    factorize_with_dynamic_threads(impl_->llt, h);
    if (impl_->llt.info() == Eigen::Success) {
      shift_ = shift;
      return true;
    }
    shift = shift == 0.0 ? 1e-10 * scale : shift * 100.0;
  }
  return false;
}

void SparseCholesky::solve(const Vector& b, Vector& x) const {
  x = impl_->llt.solve(b);
  if (impl_->llt.info() != Eigen::Success)
    fail(Status::numerical_failure, "CHOLMOD triangular solve failed");
}

}  // namespace progsim
