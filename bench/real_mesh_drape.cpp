// A real-mesh drape run progressively (issue 28 point 2): CGAL's lion head (8356 vertices) hung
// above a progressive sphere and the ground (bench/scenes/lion_drape.json), previewed on level
// 0, then refined level by level with at most MAX_SETTLES solves per level in between. Prints,
// per contact gap d̂ and level, the refinement's wall time and what it did (batches, CCD
// rounds, stopped and relaxed splits, relaxation Newton iterations, the obstacle's refinement),
// the level's solves, CGAL's count of crossing face pairs and the lowest vertex's height above
// the ground; writes the table as CSV. Needs the CGAL meshes (scripts/fetch_test_meshes.sh).
//
// usage: bench_real_mesh_drape [scene.json] [csv_path] [max_settles] [dhat ...]
//        scene: default bench/scenes/lion_drape.json, its mesh paths relative to
//        $PROGSIM_MESH_CACHE/meshes (default ~/.cache/progsim/meshes/meshes);
//        max_settles: solves per level while waiting for equilibrium (default 1: the refinement
//        is what is measured); dhat: contact gaps in m, one run each (default 1e-3 1e-4: the
//        two the issue reports).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "common/timer.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"

using namespace progsim;
namespace fs = std::filesystem;

namespace {

/// The folder of the CGAL data set's meshes, as tests/mesh/test_real_meshes.cpp finds it.
fs::path mesh_folder() {
  const char* cache = std::getenv("PROGSIM_MESH_CACHE");
  const char* home = std::getenv("HOME");
  const fs::path root =
      cache && *cache ? fs::path(cache) : fs::path(home ? home : "") / ".cache/progsim/meshes";
  return root / "meshes";
}

Scene load(const std::string& path, double dhat) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read scene " + path);
  std::stringstream text;
  text << in.rdbuf();
  Scene scene = parse_scene(text.str(), mesh_folder().string());
  scene.contact.dhat = dhat;
  return scene;
}

/// The smallest height of a shell vertex above the ground (m).
double ground_clearance(const Scene& scene, const Positions& x) {
  return (x * scene.ground.normal).minCoeff() - scene.ground.height;
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage = "bench_real_mesh_drape [scene.json] [csv_path] [max_settles] [dhat ...]";
  return bench::guarded_main(argc, argv, usage, [](int argc, char** argv) {
    const std::string scene_path =
        argc > 1 ? argv[1] : std::string(PROGSIM_SOURCE_DIR) + "/bench/scenes/lion_drape.json";
    const std::string csv_path = argc > 2 ? argv[2] : "real_mesh_drape.csv";
    const int max_settles = argc > 3 ? std::stoi(argv[3]) : 1;
    std::vector<double> gaps;
    for (int k = 4; k < argc; ++k) gaps.push_back(std::stod(argv[k]));
    if (gaps.empty()) gaps = {1e-3, 1e-4};
    std::ofstream csv = bench::open_csv(csv_path);
    csv << "scene,dhat,level,vertices,refine_seconds,batches,splits,rounds,stopped,relaxed,"
           "relaxation_iterations,obstacle_refine_rounds,obstacle_relaxed,settles,"
           "newton_iterations,solve_seconds,equilibrium,crossing_face_pairs,ground_clearance,"
           "preview_seconds\n";
    std::printf("%-10s %7s %5s %8s %9s %7s %6s %7s %7s %7s %7s %7s %9s %5s %9s %10s\n", "scene",
                "dhat", "level", "vertices", "refine s", "batches", "rounds", "stopped", "relaxed",
                "relax it", "obst rd", "settles", "Newton", "eq", "crossings", "clearance");
    for (double dhat : gaps) {
      const Scene scene = load(scene_path, dhat);
      ProgressiveSimulation psq(scene);
      Timer preview;
      for (int k = 0; k < scene.num_steps(); ++k) psq.step();
      const double preview_seconds = preview.seconds();
      for (int level = 0;; ++level) {
        for (int k = 0; k < max_settles && !psq.records()[level].equilibrium; ++k) psq.settle();
        const LevelRecord& r = psq.records()[level];
        const std::size_t crossings = psq.current().intersecting_face_pairs();
        const double clearance = ground_clearance(scene, psq.positions(level));
        const SafeRefinementStats& s = r.refinement;
        std::printf("%-10s %7.0e %5d %8lld %9.2f %7d %6d %7d %7d %7d %7d %7d %9d %5s %9zu %10.3g\n",
                    scene.name.c_str(), dhat, level,
                    static_cast<long long>(psq.positions(level).rows()), r.refine_seconds,
                    s.batches, s.rounds, s.stopped_vertices, s.relaxed_vertices,
                    s.relaxation_iterations, r.obstacle_refinement.rounds, r.settles,
                    r.newton_iterations, r.equilibrium ? "yes" : "no", crossings, clearance);
        std::fflush(stdout);
        csv << scene.name << "," << dhat << "," << level << "," << psq.positions(level).rows()
            << "," << r.refine_seconds << "," << s.batches << "," << s.splits << "," << s.rounds
            << "," << s.stopped_vertices << "," << s.relaxed_vertices << ","
            << s.relaxation_iterations << "," << r.obstacle_refinement.rounds << ","
            << r.obstacle_refinement.relaxed_vertices << "," << r.settles << ","
            << r.newton_iterations << "," << r.solve_seconds << "," << r.equilibrium << ","
            << crossings << "," << clearance << "," << preview_seconds << "\n";
        csv.flush();
        if (level == psq.finest()) break;
        psq.refine();
      }
    }
    return 0;
  });
}
