// What the Newton solver's step options buy: line-search extrapolation (NewtonSettings::
// extrapolate, the default) and CG refinement of projected steps against the exact Hessian
// (truncated_newton.hpp, opt-in). A bundled scene solved directly over its whole load script
// three times in one run per size: projected steps as they are (no extrapolation), with
// extrapolation (the default) and CG-refined as well (at most 50 CG iterations per Newton
// iteration). Prints a table, writes CSV; times are relative to the default's.
//
// usage: bench_newton_refinement [scene.json] [csv_path] [factor ...]
//        scene: a bundled scene with a generated grid or cylinder mesh (default
//        scenes/psq_twist.json, solved directly on its finest mesh); factor: each run
//        multiplies the mesh's cell counts by it (default 1 2).
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "common/timer.hpp"
#include "scaled_scene.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;

namespace {

/// CG iterations per refined step (NewtonSettings::max_cg_iterations).
constexpr int kRefinedCgIterations = 50;

/// The Newton options of one run.
struct Variant {
  const char* name;
  bool extrapolate;
  int max_cg_iterations;
};
constexpr Variant kVariants[] = {
    {"projected", false, 0}, {"extrapolated", true, 0}, {"refined", true, kRefinedCgIterations}};
constexpr int kDefault = 1;  ///< the library's default options

/// One direct run over the scene's load script.
struct Run {
  int iterations = 0, cg_iterations = 0, extrapolated_steps = 0, converged_steps = 0;
  double seconds = 0.0, energy = 0.0;
};

Run solve_directly(Scene scene, const Variant& variant) {
  scene.progressive = ProgressiveSettings{};
  scene.solver.extrapolate = variant.extrapolate;
  scene.solver.max_cg_iterations = variant.max_cg_iterations;
  Run run;
  Timer timer;
  LevelSimulation sim(scene);
  for (int s = 0; s < scene.num_steps(); ++s) {
    const StepRecord r = sim.step();
    run.iterations += r.newton.iterations;
    run.cg_iterations += r.newton.cg_iterations;
    run.extrapolated_steps += r.newton.extrapolated_steps;
    run.converged_steps += r.newton.stop == NewtonStop::converged;
    run.energy = r.newton.energy;
  }
  run.seconds = timer.seconds();
  return run;
}

int run(int argc, char** argv) {
  const std::string scene_path = argc > 1 ? argv[1] : PROGSIM_SOURCE_DIR "/scenes/psq_twist.json";
  const std::string csv_path = argc > 2 ? argv[2] : "newton_refinement.csv";
  std::vector<double> factors;
  for (int k = 3; k < argc; ++k) factors.push_back(std::stod(argv[k]));
  if (factors.empty()) factors = {1.0, 2.0};
  std::ofstream csv = bench::open_csv(csv_path);
  csv << "scene,vertices,steps,method,newton_iterations,cg_iterations,extrapolated_steps,"
         "converged_steps,seconds,final_energy,seconds_over_default\n";
  std::printf("%9s %6s %12s %8s %8s %8s %10s %9s %12s %8s\n", "vertices", "steps", "method",
              "Newton", "CG", "extrap.", "converged", "seconds", "energy (J)", "time×");
  for (double factor : factors) {
    const Scene scene = scaled_scene(scene_path, factor);
    const int vertices = scene.bodies[0].mesh.num_vertices();
    std::vector<Run> runs;
    for (const Variant& variant : kVariants) {
      std::fprintf(stderr, "%s, cells ×%g: %s\n", scene.name.c_str(), factor, variant.name);
      runs.push_back(solve_directly(scene, variant));
    }
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const Run& run = runs[k];
      const double ratio = run.seconds / runs[kDefault].seconds;
      std::printf("%9d %6d %12s %8d %8d %8d %10d %9.3g %12.6g %8.2f\n", vertices, scene.num_steps(),
                  kVariants[k].name, run.iterations, run.cg_iterations, run.extrapolated_steps,
                  run.converged_steps, run.seconds, run.energy, ratio);
      csv << scene.name << ',' << vertices << ',' << scene.num_steps() << ',' << kVariants[k].name
          << ',' << run.iterations << ',' << run.cg_iterations << ',' << run.extrapolated_steps
          << ',' << run.converged_steps << ',' << run.seconds << ',' << run.energy << ',' << ratio
          << '\n';
    }
    std::fflush(stdout);
  }
  std::printf("CSV: %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(argc, argv,
                             "bench_newton_refinement [scene.json] [csv_path] [factor ...]", run);
}
