// What the contact broad phase costs (issue 33 §1): find_candidates() on a crumpled cloth over a
// sphere obstacle, at rest (the barrier's candidate pairs), over one ordinary step's motion,
// with a fast patch (a fifth of the cloth sweeping half a metre in one step, as an impact
// does) and with a few "spike" vertices thrown a metre away. Prints a table of the median time
// per call and the pairs found, and writes CSV.
//
// usage: bench_broad_phase [csv_path] [repeats]
#include "contact/broad_phase.hpp"

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "median_seconds.hpp"
#include "mesh/mesh_generators.hpp"

using namespace progsim;

namespace {

/// A crumpled n × n cloth over a sphere, as one collision mesh.
struct ClothOverSphere {
  TriangleMesh sheet, sphere;
  CollisionMesh mesh;
};

ClothOverSphere cloth_over_sphere(int n) {
  ClothOverSphere s{make_grid(1.0, 1.0, n, n), make_sphere(0.3, 4), {}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.2, 0.2);
  const double h = 1.0 / n;
  for (Eigen::Index i = 0; i < s.sheet.vertices.rows(); ++i)
    s.sheet.vertices(i, 2) = 0.35 + noise(rng) * h + 0.05 * std::sin(9.0 * s.sheet.vertices(i, 0));
  s.sphere.vertices.rowwise() += Vec3(0.5, 0.5, 0.0).transpose();
  const std::vector<double> zero(s.sheet.num_vertices(), 0.0);
  s.mesh = build_collision_mesh(s.sheet.vertices, s.sheet.faces, zero, zero,
                                {{&s.sphere.vertices, &s.sphere.faces, 0.0}});
  return s;
}

/// The motion of one case: end positions from the start ones.
enum class Motion { rest, step, fast_patch, spikes };

const char* name_of(Motion m) {
  switch (m) {
    case Motion::rest:
      return "at rest";
    case Motion::step:
      return "one step";
    case Motion::fast_patch:
      return "fast patch";
    default:
      return "spikes";
  }
}

Positions end_positions(const ClothOverSphere& s, Motion motion) {
  Positions p1 = s.mesh.rest;
  const int shell = s.mesh.num_shell_vertices;
  const Vec3 fall(0.0, 0.0, -0.001);  // 1 mm: 10 ms at 0.1 m/s
  for (int v = 0; v < shell; ++v) {
    if (motion == Motion::step) p1.row(v) += fall.transpose();
    if (motion == Motion::fast_patch && s.mesh.rest(v, 0) < 0.2)
      p1.row(v) += Vec3(0.0, 0.0, -0.5).transpose();
    if (motion == Motion::spikes && v % 2000 == 1) p1.row(v) += Vec3(1.0, 0.7, -0.8).transpose();
  }
  return p1;
}

struct Row {
  int vertices;
  std::string motion;
  double seconds;  ///< median over the repeats
  std::size_t pairs;
};

Row measure(const ClothOverSphere& s, Motion motion, int repeats) {
  const Positions p1 = end_positions(s, motion);
  const double inflation = 2e-3;  // d̂ = 1 mm on both boxes
  CandidateSet found;
  const double seconds = bench::median_seconds(
      repeats, [&] { find_candidates(s.mesh, s.mesh.rest, p1, inflation, found); });
  return {s.sheet.num_vertices(), name_of(motion), seconds, found.size()};
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage = "bench_broad_phase [csv_path] [repeats]";
  return bench::guarded_main(argc, argv, usage, [](int argc, char** argv) {
    const std::string csv_path = argc > 1 ? argv[1] : "broad_phase.csv";
    const int repeats = argc > 2 ? std::max(1, std::stoi(argv[2])) : 9;
    std::ofstream csv = bench::open_csv(csv_path);
    csv << "vertices,motion,seconds,pairs\n";
    std::printf("%9s %-11s %12s %10s\n", "vertices", "motion", "ms per call", "pairs");
    for (int n : {100, 200}) {
      const ClothOverSphere scene = cloth_over_sphere(n);
      for (Motion m : {Motion::rest, Motion::step, Motion::fast_patch, Motion::spikes}) {
        const Row row = measure(scene, m, repeats);
        std::printf("%9d %-11s %12.2f %10zu\n", row.vertices, row.motion.c_str(), 1e3 * row.seconds,
                    row.pairs);
        csv << row.vertices << ',' << row.motion << ',' << row.seconds << ',' << row.pairs << '\n';
      }
    }
    return 0;
  });
}
