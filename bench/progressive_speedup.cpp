// What the progressive method (PSQ) buys on a bundled scene at growing sizes: coarse preview
// and the full progressive pipeline against the direct finest solve, measured in one run per
// size (progsim accuracy). Prints a table, writes CSV. Long at 40K vertices (the direct finest
// solve takes minutes to hours): not run in CI.
//
// usage: bench_progressive_speedup [--direct-time-ratio=R [--of-preview]] [scene.json]
//                                  [csv_path] [level|galerkin|both] [factor ...]
//        scene: a bundled scene whose body is a generated "grid" (nx, ny) or "cylinder"
//        (n_around, n_along) mesh (default scenes/psq_plate_buckling.json); the preview
//        preconditioner(s) (default both); factor: each run multiplies the mesh's cell counts
//        by it (default 2 4: the bundled twist's 32 × 32 grid becomes 64 × 64 and 128 × 128).
//        The scene's own levels (3, ×4 per level).
//        --direct-time-ratio=R: solve directly only the finest level (direct_coarse_error_max is
//        then nan), and stop the direct finest solve once it has taken R times the progressive
//        pipeline's time. If it stops unfinished (direct_finished = 0), the speed-ups are lower
//        bounds: the direct solve would have taken longer.
//        --of-preview: R times the coarse preview's time instead, so that a run stops as soon
//        as it shows the preview to be at least R times faster (e.g. R = 50).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "common/timer.hpp"
#include "progressive/accuracy.hpp"
#include "scaled_scene.hpp"

using namespace progsim;

namespace {

/// The scene file with its mesh's cell counts multiplied by `factor` and the given preview
/// Hessian.
Scene scaled(const std::string& path, double factor, ProxyHessian hessian) {
  Scene scene = scaled_scene(path, factor);
  scene.progressive.hessian = hessian;
  return scene;
}

/// The preview preconditioners asked for ("level", "galerkin" or "both").
std::vector<ProxyHessian> hessians(const std::string& which) {
  if (which == "level") return {ProxyHessian::level};
  if (which == "galerkin") return {ProxyHessian::galerkin};
  if (which == "both") return {ProxyHessian::level, ProxyHessian::galerkin};
  throw std::invalid_argument("unknown preconditioner '" + which + "' (level, galerkin or both)");
}

/// The row of `method` on `level`; a direct row the run did not make has NaN error.
AccuracyRow row(const AccuracyReport& r, AccuracyRow::Method method, int level) {
  for (const AccuracyRow& x : r.rows)
    if (x.method == method && x.level == level) return x;
  AccuracyRow none;
  none.error_max = std::nan("");
  return none;
}

/// Each phase and load step with the seconds since the run began, so that a run stopped by
/// hand still tells how far each part got.
bool report_phase(void* run_timer, double fraction, const char* phase) {
  const double seconds = static_cast<const Timer*>(run_timer)->seconds();
  std::fprintf(stderr, "  %8.1f s %3.0f%% %s\n", seconds, 100.0 * fraction, phase);
  return true;
}

/// The direct solves of a run: every level, or with a time ratio the finest alone.
DirectSolves direct_solves(const Scene& scene, double time_ratio, DirectSolves::TimeBase base) {
  if (time_ratio == 0.0) return {};
  return {{scene.progressive.num_coarse_levels()}, time_ratio, base};
}

int run(int argc, char** argv) {
  const std::string ratio_flag = "--direct-time-ratio=";
  const std::string preview_flag = "--of-preview";
  double time_ratio = 0.0;
  DirectSolves::TimeBase base = DirectSolves::TimeBase::pipeline;
  std::vector<std::string> args;
  for (int k = 1; k < argc; ++k)
    if (std::string(argv[k]).rfind(ratio_flag, 0) == 0)
      time_ratio = std::stod(argv[k] + ratio_flag.size());
    else if (argv[k] == preview_flag)
      base = DirectSolves::TimeBase::preview;
    else if (argv[k][0] == '-')
      throw std::invalid_argument(std::string("unknown option ") + argv[k]);
    else
      args.push_back(argv[k]);
  const std::string scene_path =
      args.size() > 0 ? args[0] : PROGSIM_SOURCE_DIR "/scenes/psq_plate_buckling.json";
  const std::string csv_path = args.size() > 1 ? args[1] : "progressive_speedup.csv";
  const std::vector<ProxyHessian> preconditioners = hessians(args.size() > 2 ? args[2] : "both");
  std::vector<double> factors;
  for (std::size_t k = 3; k < args.size(); ++k) factors.push_back(std::stod(args[k]));
  if (factors.empty()) factors = {2.0, 4.0};
  std::ofstream csv = bench::open_csv(csv_path);
  csv << "scene,vertices,levels,coarsest,proxy_hessian,preview_seconds,direct_finest_seconds,"
         "preview_speedup,progressive_seconds,progressive_speedup,refine_share,"
         "preview_error_max,direct_coarse_error_max,direct_finest_error_max,direct_finished,"
         "direct_load_steps\n";
  std::printf("%9s %6s %8s %9s %9s %8s %9s %8s %7s %9s %9s\n", "vertices", "coarse", "hessian",
              "preview s", "direct s", "preview×", "progr. s", "progr.×", "refine%", "prev.err",
              "dir0.err");
  for (double factor : factors)
    for (ProxyHessian hessian : preconditioners) {
      const char* name = hessian == ProxyHessian::level ? "level" : "galerkin";
      const Scene scene = scaled(scene_path, factor, hessian);
      std::fprintf(stderr, "%s, cells ×%g, %s preconditioner\n", scene.name.c_str(), factor, name);
      Timer run_timer;
      const AccuracyReport r = run_accuracy(scene, 500, report_phase, &run_timer,
                                            direct_solves(scene, time_ratio, base));
      int finest = 0;
      for (const AccuracyRow& x : r.rows) finest = std::max(finest, x.level);
      const AccuracyRow preview = row(r, AccuracyRow::Method::progressive, 0);
      const AccuracyRow full = row(r, AccuracyRow::Method::progressive, finest);
      const AccuracyRow direct = row(r, AccuracyRow::Method::direct, finest);
      const AccuracyRow coarse = row(r, AccuracyRow::Method::direct, 0);
      double refine = 0.0;
      for (const AccuracyRow& x : r.rows)
        if (x.method == AccuracyRow::Method::progressive) refine += x.refine_seconds;
      const char* bound = direct.finished ? " " : ">";  // stopped unfinished: lower bounds
      std::printf("%9d %6d %8s %9.3g %s%8.3g %s%7.3g %9.3g %s%7.3g %7.1f %9.3g %9.3g\n",
                  full.vertices, preview.vertices, name, preview.seconds, bound, direct.seconds,
                  bound, direct.seconds / preview.seconds, full.seconds, bound,
                  direct.seconds / full.seconds, 100.0 * refine / full.seconds, preview.error_max,
                  coarse.error_max);
      std::fflush(stdout);
      csv << scene.name << ',' << full.vertices << ',' << finest + 1 << ',' << preview.vertices
          << ',' << name << ',' << preview.seconds << ',' << direct.seconds << ','
          << direct.seconds / preview.seconds << ',' << full.seconds << ','
          << direct.seconds / full.seconds << ',' << refine / full.seconds << ','
          << preview.error_max << ',' << coarse.error_max << ',' << direct.error_max << ','
          << (direct.finished ? 1 : 0) << ',' << direct.load_steps << '\n';
    }
  std::printf("CSV: %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(
      argc, argv,
      "bench_progressive_speedup [--direct-time-ratio=R] [scene.json] [csv_path] "
      "[level|galerkin|both] [factor ...]",
      run);
}
