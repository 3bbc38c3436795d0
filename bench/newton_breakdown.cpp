// Where a Newton iteration spends its time: assembly, CHOLMOD factorization, triangular
// solves and line search, for hanging square cloths of about 2.5K, 10K and 40K vertices,
// with 1 and 2 OpenMP threads. Prints a table and writes CSV.
//
// usage: bench_newton_breakdown [csv_path] [steps_per_case] [max_grid]
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "bench_main.hpp"
#include "hanging_cloth.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;

namespace {

struct Row {
  int vertices, threads, iterations;
  NewtonTimings per_iteration;
  double step_seconds;
};

Row measure(int n, int threads, int steps) {
  omp_set_num_threads(threads);
  LevelSimulation sim(bench::hanging_cloth(n));
  Row row{sim.model().rest.num_vertices(), threads, 0, {}, 0.0};
  for (int s = 0; s < steps; ++s) {
    const StepRecord r = sim.step();
    row.iterations += r.newton.iterations;
    row.per_iteration += r.newton.timings;
    row.step_seconds += r.seconds;
  }
  const double k = std::max(1, row.iterations);
  NewtonTimings& t = row.per_iteration;
  t.assembly /= k, t.analysis /= k, t.factorization /= k, t.solve /= k, t.line_search /= k;
  row.step_seconds /= steps;
  return row;
}

int run(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "newton_breakdown.csv";
  const int steps = argc > 2 ? std::atoi(argv[2]) : 3;
  const int max_grid = argc > 3 ? std::atoi(argv[3]) : 200;
  std::ofstream csv = bench::open_csv(csv_path);
  csv << "vertices,threads,newton_iterations,assembly_ms,analysis_ms,factorization_ms,solve_ms,"
         "line_search_ms,assembly_plus_line_search_over_factorization,step_ms\n";
  std::printf("%9s %7s %6s %12s %12s %14s %9s %14s %9s %9s\n", "vertices", "threads", "iters",
              "assembly ms", "analysis ms", "factorize ms", "solve ms", "linesearch ms", "(a+ls)/f",
              "step ms");
  for (int n : {50, 100, 200}) {
    if (n > max_grid) continue;
    for (int threads : {1, 2}) {
      const Row r = measure(n, threads, steps);
      const NewtonTimings& t = r.per_iteration;
      const double ratio = (t.assembly + t.line_search) / t.factorization;
      std::printf("%9d %7d %6d %12.2f %12.2f %14.2f %9.2f %14.2f %9.2f %9.1f\n", r.vertices,
                  r.threads, r.iterations, 1e3 * t.assembly, 1e3 * t.analysis,
                  1e3 * t.factorization, 1e3 * t.solve, 1e3 * t.line_search, ratio,
                  1e3 * r.step_seconds);
      csv << r.vertices << "," << r.threads << "," << r.iterations << "," << 1e3 * t.assembly << ","
          << 1e3 * t.analysis << "," << 1e3 * t.factorization << "," << 1e3 * t.solve << ","
          << 1e3 * t.line_search << "," << ratio << "," << 1e3 * r.step_seconds << "\n";
      std::fflush(stdout);
    }
  }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(argc, argv,
                             "bench_newton_breakdown [csv_path] [steps_per_case] [max_grid]", run);
}
