// What a second core buys CHOLMOD (issue 33 §5): the projected Newton Hessian of the hanging
// cloth (bench/hanging_cloth.hpp, after one step) at about 2.6K, 10K and 40K vertices,
// factorized by CHOLMOD's supernodal and simplicial LLᵀ with OpenBLAS on 1 and 2 threads,
// with the other core idle and busy (another process spinning). The supernodal case is the
// library's own SparseCholesky (its BLAS thread setting varied). For each: the median
// factorization time, CHOLMOD's flop count over it, the speed-up over one BLAS thread, and
// whether the solution is bitwise the one-thread solution. A dense 2000² dgemm gives the
// BLAS's own rate on 1 and 2 threads for reference. Needs OpenBLAS built with pthreads (Debian:
// libopenblas0-pthread, the libblas.so.3 alternative) to vary the threads; otherwise it says
// so and measures one BLAS thread. Prints a table and writes CSV.
//
// usage: bench_cholmod_threads [csv_path] [repeats] [max_grid]
#include <dlfcn.h>

#include <Eigen/CholmodSupport>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "busy_process.hpp"
#include "common/thread_budget.hpp"
#include "hanging_cloth.hpp"
#include "median_seconds.hpp"
#include "sim/level_simulation.hpp"
#include "solve/blas_threads.hpp"
#include "solve/sparse_cholesky.hpp"

using namespace progsim;

namespace {

using SparseMatrix = Problem::SparseMatrix;

struct Case {
  int vertices = 0;
  std::string method;
  int blas_threads = 1;
  bool busy = false;
  double seconds = 0.0, gflops = 0.0, speedup = 1.0;
  bool same_bits = true;
};

/// The projected Hessian (free DOFs, lower triangle) of the cloth after one step.
SparseMatrix cloth_hessian(int n) {
  LevelSimulation sim(bench::hanging_cloth(n));
  sim.step();
  const Vector x = as_dofs(Positions(sim.positions()));
  return sim.problem().hessian(x, true);
}

/// The library's factorization (SparseCholesky: supernodal) with `c.blas_threads` BLAS threads,
/// `repeats` times, the other core busy or not; fills time and rate, returns H⁻¹1.
Vector measure_supernodal(const SparseMatrix& h, int repeats, Case& c) {
  SparseCholesky cholesky;
  cholesky.set_blas_threads(c.blas_threads);
  cholesky.analyze(h);
  std::unique_ptr<bench::BusyProcess> other =
      c.busy ? std::make_unique<bench::BusyProcess>() : nullptr;
  c.seconds = bench::median_seconds(repeats, [&] {
    if (!cholesky.factorize(h, false)) throw std::runtime_error("factorization failed");
  });
  c.gflops = cholesky.factorization_flops() / c.seconds * 1e-9;
  Vector solution;
  cholesky.solve(Vector::Ones(h.rows()), solution);
  return solution;
}

/// CHOLMOD's simplicial LLᵀ (no dense kernels, so no BLAS threads), the same way.
Vector measure_simplicial(const SparseMatrix& h, int repeats, Case& c) {
  Eigen::CholmodSimplicialLLT<SparseMatrix, Eigen::Lower> cholesky;
  cholesky.cholmod().print = 0;
  cholesky.analyzePattern(h);
  std::unique_ptr<bench::BusyProcess> other =
      c.busy ? std::make_unique<bench::BusyProcess>() : nullptr;
  c.seconds = bench::median_seconds(repeats, [&] { cholesky.factorize(h); });
  if (cholesky.info() != Eigen::Success) throw std::runtime_error("factorization failed");
  c.gflops = cholesky.cholmod().fl / c.seconds * 1e-9;
  return cholesky.solve(Vector::Ones(h.rows()));
}

/// Every (BLAS threads, other core) case of one method, against its one-thread idle case.
template <class Measure>
void measure_method(const char* method, const SparseMatrix& h, int repeats,
                    const std::vector<int>& thread_counts, Measure measure,
                    std::vector<Case>& out) {
  Vector reference;
  double reference_seconds = 0.0;
  for (bool busy : {false, true})
    for (int threads : thread_counts) {
      Case c{static_cast<int>(h.rows() / 3), method, threads, busy};
      const Vector solution = measure(h, repeats, c);
      if (reference.size() == 0) reference = solution, reference_seconds = c.seconds;
      c.speedup = reference_seconds / c.seconds;
      c.same_bits = (solution.array() == reference.array()).all();
      std::fprintf(stderr, "%d, %s, %d BLAS thread(s), %s: %.3f s\n", c.vertices, method, threads,
                   busy ? "busy" : "idle", c.seconds);
      out.push_back(c);
    }
}

/// GFLOP/s of a 2000² dgemm (the loaded BLAS's, found by dlsym) on `threads` BLAS threads.
double dgemm_gflops(int threads) {
  using Dgemm = void (*)(const char*, const char*, const int*, const int*, const int*,
                         const double*, const double*, const int*, const double*, const int*,
                         const double*, double*, const int*);
  const auto dgemm = reinterpret_cast<Dgemm>(dlsym(RTLD_DEFAULT, "dgemm_"));
  if (!dgemm) throw std::runtime_error("no dgemm_ in the loaded BLAS");
  const int n = 2000;
  const double one = 1.0, zero = 0.0;
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n);
  Eigen::MatrixXd c(n, n);
  const ScopedBlasThreads blas(threads);
  const double seconds = bench::median_seconds(3, [&] {
    dgemm("N", "N", &n, &n, &n, &one, a.data(), &n, a.data(), &n, &zero, c.data(), &n);
  });
  return 2.0 * n * n * n / seconds * 1e-9;
}

int run(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "cholmod_threads.csv";
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  const int max_grid = argc > 3 ? std::atoi(argv[3]) : 200;
  if (repeats < 1) throw std::invalid_argument("repeats must be >= 1");
  std::ofstream csv = bench::open_csv(csv_path);
  const bool can_vary = loaded_blas_threading() == BlasThreading::pthreads;
  if (!can_vary)
    std::printf("the loaded BLAS is not OpenBLAS on pthreads: one BLAS thread measured\n");
  else
    std::printf("OpenBLAS on pthreads; dgemm 2000^2: %.1f GFLOP/s on 1 thread, %.1f on 2\n",
                dgemm_gflops(1), dgemm_gflops(2));
  set_thread_budget(1);  // the matrices' assembly: not what is measured
  std::vector<Case> cases;
  const std::vector<int> threads = can_vary ? std::vector<int>{1, 2} : std::vector<int>{1};
  for (int n : {50, 100, 200}) {
    if (n > max_grid) continue;
    const SparseMatrix h = cloth_hessian(n);
    measure_method("supernodal", h, repeats, threads, measure_supernodal, cases);
    measure_method("simplicial", h, repeats, {1}, measure_simplicial, cases);
  }
  set_thread_budget(0);
  csv << "free_dofs_over_3,method,blas_threads,other_core,factorize_ms,gflops,"
         "speedup_over_1_thread_idle,same_bits_as_1_thread\n";
  std::printf("\n%9s %-11s %5s %6s %13s %8s %8s %10s\n", "DOFs/3", "method", "BLAS", "other",
              "factorize ms", "GFLOP/s", "speedup", "same bits");
  for (const Case& c : cases) {
    std::printf("%9d %-11s %5d %6s %13.1f %8.2f %8.2f %10s\n", c.vertices, c.method.c_str(),
                c.blas_threads, c.busy ? "busy" : "idle", 1e3 * c.seconds, c.gflops, c.speedup,
                c.same_bits ? "yes" : "no");
    csv << c.vertices << ',' << c.method << ',' << c.blas_threads << ','
        << (c.busy ? "busy" : "idle") << ',' << 1e3 * c.seconds << ',' << c.gflops << ','
        << c.speedup << ',' << (c.same_bits ? "yes" : "no") << '\n';
  }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(argc, argv, "bench_cholmod_threads [csv_path] [repeats] [max_grid]",
                             run);
}
