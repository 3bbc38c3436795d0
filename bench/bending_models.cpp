// What each bending model costs and how close it gets (issue 31): sheets rolled isometrically
// onto a cylinder (radius 0.4 m, ν = 0.3) about the sheet's y axis and about an axis at 45°, on
// the alternating-diagonal grid, the one-diagonal grid and the alternating grid with its
// interior vertices moved by up to 0.2 of a cell, 0.5 × 0.3 m at nx = 10 … 80 cells along:
// each model's energy over Kirchhoff's (D/2) A / R², D = E t³/(12(1 − ν²)), the closed form of
// a plate bent into a cylinder with the other curvature held at 0. Then the time of one
// evaluation of value, gradient and projected Hessian per face on the finest sheet, and the
// Hessian entries per face. Prints tables, writes CSV. Not a test: it never fails.
//
// usage: bench_bending_models [csv_path] [repetitions]
//        defaults: bench_bending_models.csv, 5
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "common/constants.hpp"
#include "energy/fitted_midedge_bending.hpp"
#include "energy/hinge_bending.hpp"
#include "energy/midedge_bending.hpp"
#include "mesh/mesh_topology.hpp"
#include "support/rolled_sheets.hpp"

using namespace progsim;
namespace ts = progsim::test_support;

namespace {

constexpr double kWidth = 0.5, kLength = 0.3, kRadius = 0.4;
const char* const kModels[] = {"hinge", "midedge", "midedge_fitted"};
const char* const kMeshes[] = {"alternating", "one_diagonal", "jittered"};

TriangleMesh sheet(int mesh, int nx) {
  const int ny = nx * 3 / 5;
  if (mesh == 1) return ts::one_diagonal_grid(kWidth, kLength, nx, ny);
  if (mesh == 2) return ts::jittered_grid(kWidth, kLength, nx, ny, 0.2);
  return make_grid(kWidth, kLength, nx, ny);
}

std::unique_ptr<EnergyTerm> bending(int model, const TriangleMesh& flat, const ShellMaterial& m) {
  const std::vector<Hinge> hinges = build_topology(flat.faces, flat.num_vertices()).hinges;
  const std::vector<ShellMaterial> materials(flat.num_faces(), m);
  if (model == 1)
    return std::make_unique<MidedgeBending>(flat.vertices, flat.faces, hinges, materials);
  if (model == 2)
    return std::make_unique<FittedMidedgeBending>(flat.vertices, flat.faces, hinges, materials);
  return std::make_unique<HingeBending>(flat.vertices, flat.faces, hinges, materials);
}

/// Seconds per face of value + gradient + projected Hessian, best of `repetitions`.
double seconds_per_face(const EnergyTerm& term, const Vector& x, int faces, int repetitions) {
  Vector g = Vector::Zero(x.size());
  std::vector<double> values(term.hessian_entry_count());
  double best = INFINITY;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    term.value(x);
    term.add_gradient(x, g);
    term.hessian_values(x, true, values.data());
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best / faces;
}

int run(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "bench_bending_models.csv";
  const int repetitions = argc > 2 ? std::stoi(argv[2]) : 5;
  if (repetitions < 1) throw std::runtime_error("repetitions must be at least 1");
  std::ofstream csv = bench::open_csv(csv_path);
  csv << "part,model,mesh,nx,axis_deg,value\n";
  ShellMaterial m;
  m.poisson_ratio = 0.3;
  const double d = m.youngs_modulus * std::pow(m.thickness, 3) / (12.0 * (1.0 - 0.09));
  const double plate = 0.5 * d * kWidth * kLength / (kRadius * kRadius);
  std::printf("E / E_plate of a sheet rolled onto a cylinder (R = %.2f m, nu = 0.3)\n", kRadius);
  std::printf("%-15s %-13s %5s %9s %9s %9s %9s\n", "model", "mesh", "axis", "nx=10", "nx=20",
              "nx=40", "nx=80");
  for (int model = 0; model < 3; ++model)
    for (int mesh = 0; mesh < 3; ++mesh)
      for (double axis_deg : {0.0, 45.0}) {
        std::printf("%-15s %-13s %5.0f", kModels[model], kMeshes[mesh], axis_deg);
        for (int nx : {10, 20, 40, 80}) {
          const TriangleMesh flat = sheet(mesh, nx);
          const double ratio =
              bending(model, flat, m)->value(ts::rolled(flat, kRadius, axis_deg * kPi / 180.0)) /
              plate;
          std::printf(" %9.4f", ratio);
          csv << "ratio," << kModels[model] << "," << kMeshes[mesh] << "," << nx << "," << axis_deg
              << "," << ratio << "\n";
        }
        std::printf("\n");
      }
  const TriangleMesh flat = sheet(2, 80);
  const Vector x = ts::rolled(flat, kRadius, kPi / 4);
  std::printf("\ncost on the jittered sheet, nx = 80 (%d faces), rolled at 45 deg, best of %d\n",
              flat.num_faces(), repetitions);
  std::printf("%-15s %14s %14s %16s\n", "model", "us/face", "vs hinge", "Hessian entries");
  double hinge_cost = 0.0;
  for (int model = 0; model < 3; ++model) {
    const std::unique_ptr<EnergyTerm> term = bending(model, flat, m);
    const double cost = seconds_per_face(*term, x, flat.num_faces(), repetitions);
    if (model == 0) hinge_cost = cost;
    const double entries = static_cast<double>(term->hessian_entry_count()) / flat.num_faces();
    std::printf("%-15s %14.3f %13.2fx %16.0f\n", kModels[model], 1e6 * cost, cost / hinge_cost,
                entries);
    csv << "us_per_face," << kModels[model] << ",jittered,80,45," << 1e6 * cost << "\n";
    csv << "hessian_entries_per_face," << kModels[model] << ",jittered,80,45," << entries << "\n";
  }
  std::printf("CSV: %s\n", csv_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(argc, argv, "bench_bending_models [csv_path] [repetitions]", run);
}
