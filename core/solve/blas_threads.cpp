#include "solve/blas_threads.hpp"

#include <dlfcn.h>

#include <mutex>

namespace progsim {
namespace {

/// OpenBLAS's own control functions (cblas.h of OpenBLAS), looked up in the library the
/// process already loaded rather than linked: CHOLMOD reaches BLAS through libblas.so.3, and a
/// build against another BLAS must still link and run.
struct OpenBlasControl {
  int (*get_parallel)() = nullptr;  // 0 serial, 1 pthreads, 2 OpenMP
  int (*get_num_threads)() = nullptr;
  void (*set_num_threads)(int) = nullptr;
};

OpenBlasControl find_openblas() {
  OpenBlasControl control;
  // RTLD_NOLOAD: only a library already mapped (as CHOLMOD's dependency); never load one.
  void* library = dlopen("libopenblas.so.0", RTLD_LAZY | RTLD_NOLOAD);
  if (!library) library = dlopen("libblas.so.3", RTLD_LAZY | RTLD_NOLOAD);
  if (!library) return control;
  control.get_parallel = reinterpret_cast<int (*)()>(dlsym(library, "openblas_get_parallel"));
  control.get_num_threads = reinterpret_cast<int (*)()>(dlsym(library, "openblas_get_num_threads"));
  control.set_num_threads =
      reinterpret_cast<void (*)(int)>(dlsym(library, "openblas_set_num_threads"));
  return control;  // the handle stays open: the pointers must outlive any unloading
}

const OpenBlasControl& openblas() {
  static const OpenBlasControl control = find_openblas();
  return control;
}

/// OpenBLAS's pool is one per process, and handles may factorize on several threads at once:
/// the first scope in saves the pool's count and sets its own, the last one out restores it,
/// and scopes in between leave it alone (they run on the first one's count).
struct OpenScopes {
  std::mutex mutex;
  int open = 0;
  int saved = 0;
};

OpenScopes& open_scopes() {
  static OpenScopes scopes;
  return scopes;
}

}  // namespace

BlasThreading loaded_blas_threading() {
  const OpenBlasControl& control = openblas();
  if (!control.get_parallel || !control.get_num_threads || !control.set_num_threads)
    return BlasThreading::unknown;
  switch (control.get_parallel()) {
    case 0:
      return BlasThreading::serial;
    case 1:
      return BlasThreading::pthreads;
    case 2:
      return BlasThreading::openmp;
    default:
      return BlasThreading::unknown;
  }
}

ScopedBlasThreads::ScopedBlasThreads(int threads) {
  if (threads < 1 || loaded_blas_threading() != BlasThreading::pthreads) return;
  OpenScopes& scopes = open_scopes();
  const std::lock_guard<std::mutex> lock(scopes.mutex);
  if (scopes.open++ == 0) {
    scopes.saved = openblas().get_num_threads();
    if (scopes.saved != threads) openblas().set_num_threads(threads);
  }
  counted_ = true;
}

ScopedBlasThreads::~ScopedBlasThreads() {
  if (!counted_) return;
  OpenScopes& scopes = open_scopes();
  const std::lock_guard<std::mutex> lock(scopes.mutex);
  if (--scopes.open == 0 && openblas().get_num_threads() != scopes.saved)
    openblas().set_num_threads(scopes.saved);
}

}  // namespace progsim
