// What a hierarchy costs: build time (decimation with intrinsic tracking, expansion coloring)
// and peak memory for meshes of about 10K, 50K and 100K vertices with 3 coarse levels (×4 per
// level), and the throughput of the direct shell prolongation P^0 (PSQ eq. 9). Each mesh is
// built in a child process so that its peak resident memory is its own. Prints a table,
// writes CSV.
//
// usage: bench_hierarchy_build [csv_path] [mesh.off ...]   (extra meshes are added as rows)
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "common/timer.hpp"
#include "hierarchy/level_prolongation.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_io.hpp"

using namespace progsim;

namespace {

struct Row {
  char name[64];
  int vertices, coarsest, levels;
  double build_seconds, peak_mib, prolong_vertices_per_second;
  int batches_coarsest;
};

TriangleMesh named_mesh(const std::string& name) {
  if (name == "sheet_101x101") return make_grid(1.0, 1.0, 100, 100);
  if (name == "sheet_224x224") return make_grid(1.0, 1.0, 223, 223);
  if (name == "sheet_317x317") return make_grid(1.0, 1.0, 316, 316);
  if (name == "sphere_40962") return make_sphere(1.0, 6);
  return read_mesh(name);
}

/// Builds, times and measures one mesh (run in a child process).
Row measure(const std::string& name) {
  const TriangleMesh mesh = named_mesh(name);
  HierarchyOptions options;
  options.coarse_vertex_counts = geometric_level_counts(mesh.num_vertices(), 4.0, 3);
  const Timer build;
  const MeshHierarchy h = build_hierarchy(mesh, options);
  Row row{};
  std::snprintf(row.name, sizeof row.name, "%s", name.substr(name.find_last_of('/') + 1).c_str());
  row.build_seconds = build.seconds();
  row.vertices = mesh.num_vertices();
  row.coarsest = h.levels[0].rest.num_vertices();
  row.levels = h.num_levels();
  row.batches_coarsest = static_cast<int>(h.expansion_batches[0].size());
  const ShellProlongation p = direct_prolongation(h, 0);
  Positions fine(mesh.num_vertices(), 3);
  const Positions coarse = h.levels[0].rest.vertices * 1.01;
  int repeats = 0;
  const Timer prolong;
  while (prolong.seconds() < 1.0 || repeats < 5) {
    p.apply(coarse, fine);
    ++repeats;
  }
  row.prolong_vertices_per_second = repeats * mesh.num_vertices() / prolong.seconds();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  row.peak_mib = usage.ru_maxrss / 1024.0;
  return row;
}

/// measure(name) in a child process; false if the child failed.
bool measure_in_child(const std::string& name, Row& row) {
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) return false;
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_ends[0]);
    try {
      const Row measured = measure(name);
      const ssize_t written = write(pipe_ends[1], &measured, sizeof measured);
      _exit(written == static_cast<ssize_t>(sizeof measured) ? 0 : 1);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
      _exit(1);
    }
  }
  close(pipe_ends[1]);
  const ssize_t got = read(pipe_ends[0], &row, sizeof row);
  close(pipe_ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return got == static_cast<ssize_t>(sizeof row) && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

int run(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "hierarchy_build.csv";
  std::vector<std::string> meshes = {"sheet_101x101", "sphere_40962", "sheet_224x224",
                                     "sheet_317x317"};
  for (int i = 2; i < argc; ++i) meshes.push_back(argv[i]);
  std::ofstream csv = bench::open_csv(csv_path);
  csv << "mesh,vertices,levels,coarsest_vertices,build_seconds,peak_mib,"
         "expansion_batches_coarsest,prolongation_vertices_per_second\n";
  std::printf("%-26s %8s %6s %8s %9s %9s %8s %14s\n", "mesh", "vertices", "levels", "coarsest",
              "build s", "peak MiB", "batches", "P^0 vertices/s");
  for (const std::string& name : meshes) {
    Row r{};
    if (!measure_in_child(name, r)) {
      std::printf("%-26s failed\n", name.c_str());
      continue;
    }
    std::printf("%-26s %8d %6d %8d %9.2f %9.1f %8d %14.3g\n", r.name, r.vertices, r.levels,
                r.coarsest, r.build_seconds, r.peak_mib, r.batches_coarsest,
                r.prolong_vertices_per_second);
    csv << r.name << ',' << r.vertices << ',' << r.levels << ',' << r.coarsest << ','
        << r.build_seconds << ',' << r.peak_mib << ',' << r.batches_coarsest << ','
        << r.prolong_vertices_per_second << '\n';
  }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(
      argc, argv,
      "bench_hierarchy_build [csv_path] [mesh.off ...]   (extra meshes are added as rows)", run);
}
