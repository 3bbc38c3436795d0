// Our side of the contact comparison with IPC Toolkit (bench/contact_peer.py runs both on the
// same frames): reads one frame pair (a triangle mesh at the start and end of a linear step),
// times our broad phase, barrier value, gradient and Hessian, and additive CCD on it, and
// prints one JSON object with the medians and the counts (candidates, active pairs, step).
//
// usage: bench_contact_peer frames.bin dhat threads [repeats]
//   frames.bin: int64 |V|, int64 |F|, then float64 V0 (|V| x 3), float64 V1 (|V| x 3) and
//   int32 F (|F| x 3), all row-major, native byte order
#include <Eigen/SparseCore>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "common/thread_budget.hpp"
#include "contact/broad_phase.hpp"
#include "contact/contact_potential.hpp"
#include "median_seconds.hpp"
#include "problem/problem.hpp"

using namespace progsim;
using progsim::bench::median_seconds;

namespace {

struct Frames {
  Positions start, end;
  Faces faces;
};

template <class T>
void read_exactly(std::ifstream& in, T* data, std::size_t count, const std::string& path) {
  in.read(reinterpret_cast<char*>(data), static_cast<std::streamsize>(count * sizeof(T)));
  if (!in) throw std::runtime_error(path + ": shorter than its header says");
}

Frames read_frames(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::int64_t counts[2];
  read_exactly(in, counts, 2, path);
  if (counts[0] < 3 || counts[1] < 1 || counts[0] > 50'000'000 || counts[1] > 100'000'000)
    throw std::runtime_error(path + ": implausible vertex or face count");
  Frames f{Positions(counts[0], 3), Positions(counts[0], 3), Faces(counts[1], 3)};
  read_exactly(in, f.start.data(), f.start.size(), path);
  read_exactly(in, f.end.data(), f.end.size(), path);
  read_exactly(in, f.faces.data(), f.faces.size(), path);
  if (f.faces.minCoeff() < 0 || f.faces.maxCoeff() >= counts[0])
    throw std::runtime_error(path + ": a face index is out of range");
  return f;
}

Vector dofs_of(const Positions& p) {
  return Eigen::Map<const Vector>(p.data(), p.size());
}

int run(int argc, char** argv) {
  if (argc < 4) throw std::invalid_argument("frames.bin, dhat and threads are required");
  const Frames frames = read_frames(argv[1]);
  const double dhat = std::stod(argv[2]);
  set_thread_budget(std::stoi(argv[3]));
  const int repeats = argc > 4 ? std::stoi(argv[4]) : 5;
  if (!(dhat > 0) || repeats < 1) throw std::invalid_argument("dhat and repeats must be > 0");

  const Eigen::Index n = frames.start.rows();
  const std::vector<double> no_offset(n, 0.0), no_friction(n, 0.0);
  const CollisionMesh mesh =
      build_collision_mesh(frames.start, frames.faces, no_offset, no_friction, {});
  CandidateSet static_set, swept_set;
  const double t_static = median_seconds(
      repeats, [&] { find_candidates(mesh, frames.start, frames.start, dhat, static_set); });
  const double t_swept = median_seconds(
      repeats, [&] { find_candidates(mesh, frames.start, frames.end, dhat, swept_set); });

  // The barrier over the static candidates at the start (IPC eq. 7), κ = 1 N/m³, in a Problem
  // of its own: the Hessian is assembled as the Newton solver gets it (lower triangle).
  Problem problem(static_cast<int>(3 * n));
  ContactPotential& barrier = problem.add_term(
      std::make_unique<ContactPotential>(mesh, dhat, 1.0, std::optional<GroundPlane>{}));
  problem.finalize();
  const Vector x = dofs_of(frames.start);
  problem.begin_solve(x);
  // Value and gradient measure their pairs once per position (begin_solve() above measured x
  // already); the solver takes the gradient where the line search evaluated the energy, so the
  // gradient is timed after an untimed value at the same x (as theirs after the collision
  // set's build). Repeats alternate between x and x moved 1e-12 m, so that each value measures
  // every candidate as a new line-search point does.
  const Vector x_moved = x + Vector::Constant(x.size(), 1e-12);
  int calls = 0;
  const Vector* position = &x;
  const auto next_position = [&] { position = ++calls % 2 ? &x_moved : &x; };
  double energy = 0;
  const double t_value =
      bench::median_seconds_after(repeats, next_position, [&] { barrier.value(*position); });
  Vector gradient(x.size());
  const double t_gradient = bench::median_seconds_after(
      repeats,
      [&] {
        next_position();
        barrier.value(*position);
      },
      [&] {
        gradient.setZero();
        barrier.add_gradient(*position, gradient);
      });
  energy = barrier.value(x);
  gradient.setZero();
  barrier.add_gradient(x, gradient);
  // The first assembly builds the matrix's pattern; later ones with the same contact set keep
  // it and only write values (Problem::add_changing_pattern_terms).
  const double t_hessian_new_pattern = median_seconds(1, [&] { problem.hessian(x, true); });
  const std::int64_t active_before = barrier.stats().active_pairs;
  const double t_hessian = median_seconds(repeats, [&] { problem.hessian(x, true); });
  const std::int64_t active = (barrier.stats().active_pairs - active_before) / repeats;
  const Eigen::Index hessian_nonzeros = problem.hessian(x, true).nonZeros();
  std::vector<Eigen::Triplet<double>> triplets;
  const double t_triplets = median_seconds(repeats, [&] {
    triplets.clear();
    barrier.append_hessian_triplets(x, true, triplets);
  });

  // CCD of the whole step: its broad phase (swept boxes grown by d̂) and additive CCD.
  const Vector step = dofs_of(frames.end) - x;
  double alpha = 0;
  const double ccd_before = barrier.stats().ccd_seconds;
  const double t_ccd_step = median_seconds(repeats, [&] { alpha = barrier.max_step(x, step); });
  const double t_ccd_narrow = (barrier.stats().ccd_seconds - ccd_before) / repeats;

  std::printf(
      "{\"vertices\": %ld, \"faces\": %ld, \"threads\": %d, \"static_vf\": %zu, "
      "\"static_ee\": %zu, \"swept_vf\": %zu, \"swept_ee\": %zu, \"active\": %ld, "
      "\"energy\": %.17g, \"gradient_norm\": %.17g, \"hessian_nonzeros\": %ld, \"alpha\": %.17g, "
      "\"broad_static\": %.6g, \"broad_swept\": %.6g, \"value\": %.6g, \"gradient\": %.6g, "
      "\"hessian\": %.6g, \"hessian_new_pattern\": %.6g, \"hessian_triplets\": %.6g, "
      "\"ccd_narrow\": %.6g, \"ccd_step\": %.6g}\n",
      static_cast<long>(n), static_cast<long>(frames.faces.rows()), thread_budget(),
      static_set.vertex_face.size(), static_set.edge_edge.size(), swept_set.vertex_face.size(),
      swept_set.edge_edge.size(), static_cast<long>(active), energy, gradient.norm(),
      static_cast<long>(hessian_nonzeros), alpha, t_static, t_swept, t_value, t_gradient, t_hessian,
      t_hessian_new_pattern, t_triplets, t_ccd_narrow, t_ccd_step);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main(argc, argv, "bench_contact_peer frames.bin dhat threads [repeats]",
                             run);
}
