// Speed on a shared machine without environment variables (issue 33 §6): the contact
// benchmark's cloth on a sphere (default 61² = 3721 vertices, 20 steps) timed with the other
// core idle and with another process spinning on it, for each thread setting of the library:
// automatic (the default, thread_budget.hpp), 2 fixed (every large loop on a team of two, as
// before the budget) and 1. Run it WITHOUT OMP_WAIT_POLICY: the point is OpenMP's default
// (spinning) wait policy, which an embedding engine cannot be asked to change. Prints a table
// (seconds, Newton iterations, threads at the end) and the busy/quiet ratio per setting, and
// writes CSV.
//
// usage: bench_busy_core [csv_path] [grid_n] [steps]
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "busy_process.hpp"
#include "cloth_over_sphere.hpp"
#include "common/thread_budget.hpp"
#include "common/timer.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;

namespace {

struct Run {
  int setting = 0;
  bool busy = false;
  double seconds = 0.0;
  int newton_iterations = 0;
  int threads_at_end = 0;
};

Run timed_run(const Scene& scene, int setting, bool busy, int steps) {
  set_thread_budget(setting);
  Run run{setting, busy};
  LevelSimulation sim(scene);
  std::unique_ptr<bench::BusyProcess> other =
      busy ? std::make_unique<bench::BusyProcess>() : nullptr;
  Timer timer;
  for (int s = 0; s < steps; ++s) run.newton_iterations += sim.step().newton.iterations;
  run.seconds = timer.seconds();
  run.threads_at_end = thread_budget();
  std::fprintf(stderr, "threads %s, %s: %.1f s\n",
               setting == 0 ? "auto" : std::to_string(setting).c_str(), busy ? "busy" : "quiet",
               run.seconds);
  return run;
}

int run(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "busy_core.csv";
  const int n = argc > 2 ? std::atoi(argv[2]) : 60;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 20;
  if (n < 2 || steps < 1) throw std::invalid_argument("grid_n must be >= 2 and steps >= 1");
  const char* wait_policy = std::getenv("OMP_WAIT_POLICY");
  std::printf("cloth %d vertices on a sphere, %d steps; OMP_WAIT_POLICY %s\n", (n + 1) * (n + 1),
              steps, wait_policy ? wait_policy : "unset (OpenMP's default)");
  const Scene scene = bench::cloth_over_sphere(n, steps, true);
  std::vector<Run> runs;
  for (int setting : {0, 2, 1})
    for (bool busy : {false, true}) runs.push_back(timed_run(scene, setting, busy, steps));

  std::ofstream csv = bench::open_csv(csv_path);
  csv << "threads_setting,other_core,seconds,newton_iterations,threads_at_end\n";
  std::printf("\n%-10s %-6s %9s %7s %8s\n", "threads", "other", "seconds", "newton", "threads@end");
  for (const Run& r : runs) {
    const std::string name = r.setting == 0 ? "auto" : std::to_string(r.setting);
    std::printf("%-10s %-6s %9.2f %7d %8d\n", name.c_str(), r.busy ? "busy" : "idle", r.seconds,
                r.newton_iterations, r.threads_at_end);
    csv << name << ',' << (r.busy ? "busy" : "idle") << ',' << r.seconds << ','
        << r.newton_iterations << ',' << r.threads_at_end << '\n';
  }
  std::printf("\nbusy / idle:");
  for (std::size_t k = 0; k + 1 < runs.size(); k += 2)
    std::printf("  %s %.2fx",
                runs[k].setting == 0 ? "auto" : std::to_string(runs[k].setting).c_str(),
                runs[k + 1].seconds / runs[k].seconds);
  std::printf("\nwrote %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(argc, argv, "bench_busy_core [csv_path] [grid_n] [steps]", run);
}
