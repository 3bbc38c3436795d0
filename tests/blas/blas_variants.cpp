// The factorization under each OpenBLAS build Debian offers as libblas.so.3 (issue 33 §5):
// ctest runs this executable once per installed variant, with LD_LIBRARY_PATH pointing at it
// and PROGSIM_EXPECTED_BLAS naming it ("pthreads" or "openmp"). Whichever BLAS the system
// chose, the library's factorization runs the dense kernels on one thread unless asked, so
// results do not depend on the BLAS's own thread count and do not collapse under load
// (bench/results/cholmod_threads.csv: 2 BLAS threads with the other core busy ran 6.3x slower).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "solve/blas_threads.hpp"
#include "solve/sparse_cholesky.hpp"

using namespace progsim;

namespace {

/// The variant ctest loaded, as it names it; empty when run outside ctest.
std::string expected_blas() {
  const char* name = std::getenv("PROGSIM_EXPECTED_BLAS");
  return name ? name : "";
}

/// OpenBLAS's own thread count functions, read independently of solve/blas_threads.cpp.
struct OpenBlasThreads {
  int (*get)() = nullptr;
  void (*set)(int) = nullptr;
};

OpenBlasThreads openblas_threads() {
  OpenBlasThreads threads;
  threads.get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  threads.set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  return threads;
}

/// A 2D-grid stiffness-like SPD matrix (3 DOFs per node, two rings of neighbours, lower
/// triangle): about 30K DOFs at n = 100, whose top supernodes are large enough for OpenBLAS to
/// split its kernels between threads.
SparseCholesky::SparseMatrix grid_matrix(int n) {
  std::vector<Eigen::Triplet<double>> entries;
  const auto couple = [&](int a, int b) {
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) {
        const double value = p == q ? 1.0 : 0.1;
        entries.emplace_back(3 * a + p, 3 * a + q, value);
        entries.emplace_back(3 * b + p, 3 * b + q, value);
        entries.emplace_back(3 * std::max(a, b) + p, 3 * std::min(a, b) + q, -value);
      }
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int node = i * n + j;
      if (i + 1 < n) couple(node, node + n);
      if (j + 1 < n) couple(node, node + 1);
      if (i + 1 < n && j + 1 < n) couple(node, node + n + 1);
      if (i + 2 < n) couple(node, node + 2 * n);
      if (j + 2 < n) couple(node, node + 2);
    }
  for (int k = 0; k < 3 * n * n; ++k) entries.emplace_back(k, k, 1e-2);
  SparseCholesky::SparseMatrix h(3 * n * n, 3 * n * n);
  h.setFromTriplets(entries.begin(), entries.end());
  return h;
}

/// H⁻¹1 by the library's factorization, with OpenBLAS's own pool set to `pool` beforehand.
Vector solve_with_pool(const SparseCholesky::SparseMatrix& h, int pool) {
  openblas_threads().set(pool);
  SparseCholesky cholesky;
  EXPECT_TRUE(cholesky.factorize(h, false));
  Vector x;
  cholesky.solve(Vector::Ones(h.rows()), x);
  return x;
}

}  // namespace

TEST(BlasVariant, TheLoadedBlasIsTheVariantCtestChose) {
  const std::string expected = expected_blas();
  ASSERT_TRUE(expected == "pthreads" || expected == "openmp")
      << "run through ctest: PROGSIM_EXPECTED_BLAS names the variant (got '" << expected << "')";
  EXPECT_EQ(loaded_blas_threading(),
            expected == "pthreads" ? BlasThreading::pthreads : BlasThreading::openmp);
}

TEST(BlasVariant, AThreadScopeSetsOnlyAPthreadPoolAndRestoresIt) {
  const OpenBlasThreads threads = openblas_threads();
  ASSERT_TRUE(threads.get && threads.set) << "OpenBLAS is not loaded";
  threads.set(2);
  {
    const ScopedBlasThreads scope(1);
    EXPECT_EQ(threads.get(), expected_blas() == "pthreads" ? 1 : 2);
  }
  EXPECT_EQ(threads.get(), 2);
}

// Two handles factorizing on two threads: the first scope in sets the pool; the second, which
// ends after the first, must still run on that count, and the last one out restores the pool.
TEST(BlasVariant, OverlappingScopesKeepTheirCountUntilTheLastOneEnds) {
  const OpenBlasThreads threads = openblas_threads();
  ASSERT_TRUE(threads.get && threads.set) << "OpenBLAS is not loaded";
  const bool pthreads = expected_blas() == "pthreads";
  threads.set(2);
  std::optional<ScopedBlasThreads> first(std::in_place, 1);
  std::optional<ScopedBlasThreads> second(std::in_place, 1);
  first.reset();
  EXPECT_EQ(threads.get(), pthreads ? 1 : 2) << "the pool changed under the open scope";
  second.reset();
  EXPECT_EQ(threads.get(), 2);
}

TEST(BlasVariant, FactorsAreTheSameToTheBitWhateverOpenBlasPoolTheProcessSet) {
  const SparseCholesky::SparseMatrix h = grid_matrix(100);
  const Vector one = solve_with_pool(h, 1);
  const Vector two = solve_with_pool(h, 2);
  ASSERT_TRUE(one.allFinite());
  EXPECT_LT(
      (h.selfadjointView<Eigen::Lower>() * one - Vector::Ones(h.rows())).lpNorm<Eigen::Infinity>(),
      1e-6);
  EXPECT_TRUE((one.array() == two.array()).all())
      << "max difference " << (one - two).cwiseAbs().maxCoeff();
}

TEST(BlasVariant, BlasThreadsBelowOneAreRefused) {
  SparseCholesky cholesky;
  EXPECT_THROW(cholesky.set_blas_threads(0), Error);
  EXPECT_NO_THROW(cholesky.set_blas_threads(2));
}
