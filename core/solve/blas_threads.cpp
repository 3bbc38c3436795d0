#include "solve/blas_threads.hpp"

#include <dlfcn.h>

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
  dlclose(library);  // drops only the reference taken here
  return control;
}

const OpenBlasControl& openblas() {
  static const OpenBlasControl control = find_openblas();
  return control;
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
  const int current = openblas().get_num_threads();
  if (current == threads) return;
  previous_ = current;
  openblas().set_num_threads(threads);
}

ScopedBlasThreads::~ScopedBlasThreads() {
  if (previous_ > 0) openblas().set_num_threads(previous_);
}

}  // namespace progsim
