// What a progressive animation buys (issues 29 and 32's benchmarks; PD §5.2 reports preview
// speed-ups of 21–75× against direct fine simulation, VPD 10–120×): in one run, the preview
// (level 0: PD's proxy energy on a shell, VPD's own tet level on a solid), every refined level,
// a direct simulation of the coarsest level and of the finest, each over the same steps.
// Prints a table and writes CSV: wall time, time per step, Newton iterations per step and peak
// resident memory per phase, then the ratios. Long at 35K vertices (hours): not run in CI.
//
// usage: bench_progressive_dynamics [--direct-time-ratio=R] [--coarsest-only] [scene.json]
//                                   [csv_path] [factor]
//        scene: a dynamic scene with a "progressive" section whose body is a generated "grid"
//        (PD; default bench/scenes/pd_drape.json) or "tet_box" (VPD); factor multiplies its
//        cell counts (default 1; 4.6 gives the 34.6K-vertex drape).
//        --direct-time-ratio=R: stop the direct finest simulation once it has taken R times the
//        preview's time (default 200); its time over all steps is then extrapolated from its
//        mean step, and the preview speed-up is marked as a bound.
//        --coarsest-only: the preview and the direct coarsest simulation alone (the preview's
//        overhead over the mesh it animates, in minutes where the whole run takes an hour).
#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "common/timer.hpp"
#include "progressive/progressive_animation.hpp"
#include "scaled_scene.hpp"

using namespace progsim;

namespace {

/// One phase of the run: a level animated progressively or directly.
struct Phase {
  std::string name;
  int vertices = 0;
  int steps = 0;         ///< steps taken
  double seconds = 0.0;  ///< wall time of the steps taken
  int newton_iterations = 0;
  double peak_mib = 0.0;  ///< peak resident memory during the phase (MiB)
  bool finished = true;   ///< every step taken (false: stopped by the time ratio)
};

/// Resets the kernel's peak-RSS counter (Linux: writing 5 to clear_refs resets VmHWM).
void reset_peak_memory() {
  std::ofstream("/proc/self/clear_refs") << "5";
}

/// Peak resident memory since the last reset (MiB), from /proc/self/status.
double peak_memory_mib() {
  std::ifstream status("/proc/self/status");
  std::string key;
  double kib = 0.0;
  while (status >> key) {
    if (key == "VmHWM:") {
      status >> kib;
      break;
    }
    status.ignore(1 << 12, '\n');
  }
  return kib / 1024.0;
}

/// A direct simulation of `level` for at most `steps` steps or until `time_limit` seconds have
/// passed.
Phase direct_phase(const ProgressiveAnimation& pd, int level, int steps, double time_limit) {
  reset_peak_memory();
  const std::unique_ptr<LevelSimulation> level_sim = pd.direct_level(level);
  LevelSimulation& sim = *level_sim;
  Phase p{"direct level " + std::to_string(level), sim.model().rest.num_vertices()};
  Timer timer;
  for (; p.steps < steps && timer.seconds() < time_limit; ++p.steps)
    p.newton_iterations += sim.step().newton.iterations;
  p.seconds = timer.seconds();
  p.finished = p.steps == steps;
  p.peak_mib = peak_memory_mib();
  std::fprintf(stderr, "%s: %d steps in %.1f s\n", p.name.c_str(), p.steps, p.seconds);
  return p;
}

/// The preview over `steps` steps.
Phase preview_phase(ProgressiveAnimation& pd, int steps) {
  reset_peak_memory();
  for (int n = 0; n < steps; ++n) pd.step_preview();
  const DynamicLevelRecord& r = pd.record(0);
  Phase p{"preview (level 0)", r.vertices, steps, r.seconds, r.newton_iterations};
  p.peak_mib = peak_memory_mib();
  std::fprintf(stderr, "%s: %.1f s\n", p.name.c_str(), p.seconds);
  return p;
}

/// The next level refined over the previewed steps.
Phase refine_phase(ProgressiveAnimation& pd) {
  reset_peak_memory();
  pd.refine([](int done, int total) {
    std::fprintf(stderr, "\rrefining: step %d/%d", done, total);
    return true;
  });
  const DynamicLevelRecord& r = pd.record(pd.level());
  Phase p{"refined level " + std::to_string(pd.level()), r.vertices,
          static_cast<int>(r.steps.size()), r.seconds, r.newton_iterations};
  p.peak_mib = peak_memory_mib();
  std::fprintf(stderr, "\n%s: %.1f s\n", p.name.c_str(), p.seconds);
  return p;
}

double per_step(const Phase& p) {
  return p.steps > 0 ? p.seconds / p.steps : 0.0;
}

void print_and_write(const std::vector<Phase>& phases, std::ofstream& csv) {
  std::printf("%-22s %8s %6s %10s %10s %8s %9s %s\n", "phase", "vertices", "steps", "seconds",
              "s/step", "newton/s", "peak MiB", "finished");
  csv << "phase,vertices,steps,seconds,seconds_per_step,newton_per_step,peak_mib,finished\n";
  for (const Phase& p : phases) {
    const double its = p.steps > 0 ? double(p.newton_iterations) / p.steps : 0.0;
    std::printf("%-22s %8d %6d %10.2f %10.4f %8.1f %9.1f %s\n", p.name.c_str(), p.vertices, p.steps,
                p.seconds, per_step(p), its, p.peak_mib, p.finished ? "yes" : "no");
    csv << p.name << ',' << p.vertices << ',' << p.steps << ',' << p.seconds << ',' << per_step(p)
        << ',' << its << ',' << p.peak_mib << ',' << p.finished << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage =
      "bench_progressive_dynamics [--direct-time-ratio=R] [--coarsest-only] [scene.json] "
      "[csv_path] [factor]";
  return bench::guarded_main(argc, argv, usage, [](int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    double ratio = 200.0;
    bool coarsest_only = false;
    while (!args.empty() && args[0].rfind("--", 0) == 0) {
      if (args[0].rfind("--direct-time-ratio=", 0) == 0)
        ratio = std::stod(args[0].substr(20));
      else if (args[0] == "--coarsest-only")
        coarsest_only = true;
      else
        throw std::invalid_argument("unknown option " + args[0]);
      args.erase(args.begin());
    }
    const std::string path =
        args.size() > 0 ? args[0] : std::string(PROGSIM_SOURCE_DIR) + "/bench/scenes/pd_drape.json";
    const std::string csv_path = args.size() > 1 ? args[1] : "progressive_dynamics.csv";
    const double factor = args.size() > 2 ? std::stod(args[2]) : 1.0;
    std::ofstream csv = bench::open_csv(csv_path);
    const Scene scene = scaled_scene(path, factor);
    const int steps = scene.num_steps();
    const std::unique_ptr<ProgressiveAnimation> run = make_progressive_animation(scene);
    ProgressiveAnimation& pd = *run;
    std::fprintf(stderr, "%s, %d levels\n", pd.method(), pd.finest() + 1);
    std::vector<Phase> phases{preview_phase(pd, steps)};
    const double preview = phases[0].seconds;
    if (coarsest_only) {
      phases.push_back(direct_phase(pd, 0, steps, 1e30));
      print_and_write(phases, csv);
      std::printf("\npreview against direct coarsest: %.2fx its time\n",
                  preview / phases[1].seconds);
      return 0;
    }
    while (pd.level() < pd.finest()) phases.push_back(refine_phase(pd));
    phases.push_back(direct_phase(pd, 0, steps, 1e30));
    phases.push_back(direct_phase(pd, pd.finest(), steps, ratio * preview));
    print_and_write(phases, csv);
    const Phase& direct_finest = phases.back();
    const Phase& direct_coarsest = phases[phases.size() - 2];
    const Phase& pd_finest = phases[phases.size() - 3];
    const double direct_total = per_step(direct_finest) * steps;  // extrapolated if stopped
    std::printf("\npreview against direct finest:   %.1fx%s\n", direct_total / preview,
                direct_finest.finished ? ""
                                       : " (direct stopped early: extrapolated from its mean "
                                         "step, its first steps before contact are cheapest)");
    std::printf("preview against direct coarsest: %.2fx its time\n",
                preview / direct_coarsest.seconds);
    std::printf("refined finest step against direct finest step: %.2fx\n",
                per_step(pd_finest) / per_step(direct_finest));
    return 0;
  });
}
