// What the progressive method (PSQ) buys on a bundled grid scene at growing sizes: coarse
// preview and the full progressive pipeline against the direct finest solve, measured in one
// run per size (progsim accuracy), with both preview preconditioners. Prints a table, writes
// CSV. Long at 40K vertices (the direct finest solve takes minutes to hours): not run in CI.
//
// usage: bench_progressive_speedup [scene.json] [csv_path] [grid_cells ...]
//        scene: a bundled scene whose body is a "grid" mesh (default
//        scenes/psq_plate_buckling.json); grid_cells: the grid's nx = ny per run (default 50 100
//        200: 2 601, 10 201 and 40 401 vertices); the scene's own levels (3, ×4 per level)
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "progressive/accuracy.hpp"
#include "scene/scene_json.hpp"

using namespace progsim;

namespace {

/// The scene file with its grid resized to cells × cells and the given preview Hessian.
Scene scaled(const std::string& path, int cells, ProxyHessian hessian) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  const std::regex grid("\"(nx|ny)\": *[0-9]+");
  const std::string json = std::regex_replace(text.str(), grid, "\"$1\": " + std::to_string(cells));
  Scene scene = parse_scene(json, path.substr(0, path.find_last_of('/') + 1));
  scene.progressive.hessian = hessian;
  return scene;
}

const AccuracyRow& row(const AccuracyReport& r, AccuracyRow::Method method, int level) {
  for (const AccuracyRow& x : r.rows)
    if (x.method == method && x.level == level) return x;
  return r.rows.front();
}

bool report_phase(void*, double fraction, const char* phase) {
  std::fprintf(stderr, "  %3.0f%% %s\n", 100.0 * fraction, phase);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string scene_path =
      argc > 1 ? argv[1] : PROGSIM_SOURCE_DIR "/scenes/psq_plate_buckling.json";
  const std::string csv_path = argc > 2 ? argv[2] : "progressive_speedup.csv";
  std::vector<int> sizes;
  for (int k = 3; k < argc; ++k) sizes.push_back(std::stoi(argv[k]));
  if (sizes.empty()) sizes = {50, 100, 200};
  std::ofstream csv(csv_path);
  csv << "scene,vertices,levels,coarsest,proxy_hessian,preview_seconds,direct_finest_seconds,"
         "preview_speedup,progressive_seconds,progressive_speedup,refine_share,"
         "preview_error_max,direct_coarse_error_max,direct_finest_error_max\n";
  std::printf("%9s %6s %8s %9s %9s %8s %9s %8s %7s %9s %9s\n", "vertices", "coarse", "hessian",
              "preview s", "direct s", "preview×", "progr. s", "progr.×", "refine%", "prev.err",
              "dir0.err");
  for (int cells : sizes)
    for (ProxyHessian hessian : {ProxyHessian::level, ProxyHessian::galerkin}) {
      const char* name = hessian == ProxyHessian::level ? "level" : "galerkin";
      const Scene scene = scaled(scene_path, cells, hessian);
      std::fprintf(stderr, "%s %d×%d, %s preconditioner\n", scene.name.c_str(), cells, cells, name);
      const AccuracyReport r = run_accuracy(scene, 500, report_phase, nullptr);
      int finest = 0;
      for (const AccuracyRow& x : r.rows) finest = std::max(finest, x.level);
      const AccuracyRow& preview = row(r, AccuracyRow::Method::progressive, 0);
      const AccuracyRow& full = row(r, AccuracyRow::Method::progressive, finest);
      const AccuracyRow& direct = row(r, AccuracyRow::Method::direct, finest);
      const AccuracyRow& coarse = row(r, AccuracyRow::Method::direct, 0);
      double refine = 0.0;
      for (const AccuracyRow& x : r.rows)
        if (x.method == AccuracyRow::Method::progressive) refine += x.refine_seconds;
      std::printf("%9d %6d %8s %9.3g %9.3g %8.3g %9.3g %8.3g %7.1f %9.3g %9.3g\n", full.vertices,
                  preview.vertices, name, preview.seconds, direct.seconds,
                  direct.seconds / preview.seconds, full.seconds, direct.seconds / full.seconds,
                  100.0 * refine / full.seconds, preview.error_max, coarse.error_max);
      std::fflush(stdout);
      csv << scene.name << ',' << full.vertices << ',' << finest + 1 << ',' << preview.vertices
          << ',' << name << ',' << preview.seconds << ',' << direct.seconds << ','
          << direct.seconds / preview.seconds << ',' << full.seconds << ','
          << direct.seconds / full.seconds << ',' << refine / full.seconds << ','
          << preview.error_max << ',' << coarse.error_max << ',' << direct.error_max << '\n';
    }
  std::printf("CSV: %s\n", csv_path.c_str());
  return 0;
}
