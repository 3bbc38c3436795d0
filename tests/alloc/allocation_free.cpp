// Hot paths that must not allocate (STYLE 14): the prolongation operators' apply(), offsets()
// and the chain rule add_jacobian_transpose(), called once per Newton iteration of a preview;
// the contact barrier's value, gradient and assembled Hessian within one contact set. A
// separate executable counts every malloc/calloc/realloc in the process (interposing glibc's
// allocator, which libprogsim and Eigen reach through malloc) around the calls; sanitizer builds,
// which own malloc, skip it.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <cstddef>

#include "contact/collision_mesh.hpp"
#include "contact/contact_potential.hpp"
#include "energy/fitted_midedge_bending.hpp"
#include "energy/hinge_bending.hpp"
#include "energy/midedge_bending.hpp"
#include "energy/neo_hookean_membrane.hpp"
#include "energy/prolonged_elastics.hpp"
#include "hierarchy/barycentric_prolongation.hpp"
#include "hierarchy/level_prolongation.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_topology.hpp"
#include "problem/problem.hpp"
#include "support/stacked_sheets.hpp"

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void __libc_free(void* pointer);
}

namespace {
std::atomic<long> allocations{0};
}  // namespace

extern "C" {
void* malloc(std::size_t size) {
  ++allocations;
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  ++allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) {
  ++allocations;
  return __libc_realloc(pointer, size);
}
void free(void* pointer) {
  __libc_free(pointer);
}
}

using namespace progsim;

namespace {

/// Allocations made by `work`.
template <class Work>
long allocations_in(Work&& work) {
  const long before = allocations.load();
  work();
  return allocations.load() - before;
}

TEST(AllocationFree, ProlongationApplyAndOffsets) {
  // 3721 fine vertices: above the 2048 at which the loops go parallel.
  const TriangleMesh sheet = make_grid(1.0, 1.0, 60, 60);
  HierarchyOptions options;
  options.coarse_vertex_counts = {150};
  const MeshHierarchy h = build_hierarchy(sheet, options);
  const ShellProlongation shell = direct_prolongation(h, 0);
  const BarycentricProlongation linear(h.levels[0].rest.faces, h.levels[0].rest.num_vertices(),
                                       h.to_finest[0]);
  const Positions coarse = h.levels[0].rest.vertices * 1.01;
  Positions fine(sheet.num_vertices(), 3), offsets(sheet.num_vertices(), 3);
  Positions coarse_gradient = Positions::Zero(coarse.rows(), 3);
  std::vector<Eigen::Matrix<double, 9, 1>> workspace;
  ASSERT_GT(allocations.load(), 0) << "the counting allocator is not in use";
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    shell.apply(coarse, fine);  // warm-up: OpenMP creates its thread team once
    shell.add_jacobian_transpose(coarse, fine, coarse_gradient, workspace);  // sizes workspace
    const long count = allocations_in([&] {
      for (int k = 0; k < 10; ++k) {
        shell.apply(coarse, fine);
        shell.offsets(coarse, offsets);
        linear.apply(coarse, fine);
        shell.add_jacobian_transpose(coarse, fine, coarse_gradient, workspace);
      }
    });
    EXPECT_EQ(count, 0) << threads << " thread(s)";
  }
}

TEST(AllocationFree, ProxyEnergyValueAndGradient) {
  // The preview's proxy Ψ_L(P(x)) through two composed operators (PSQ eqs. 2 and 7).
  const TriangleMesh sheet = make_grid(1.0, 1.0, 60, 60);
  HierarchyOptions options;
  options.coarse_vertex_counts = {150, 600};
  const MeshHierarchy h = build_hierarchy(sheet, options);
  const std::vector<ShellMaterial> materials(sheet.num_faces());
  std::vector<std::unique_ptr<EnergyTerm>> finest;
  finest.push_back(std::make_unique<NeoHookeanMembrane>(sheet.vertices, sheet.faces, materials));
  finest.push_back(std::make_unique<HingeBending>(
      sheet.vertices, sheet.faces, build_topology(sheet.faces, sheet.num_vertices()).hinges,
      materials));
  const ProlongedElastics proxy(
      {std::make_shared<const ShellProlongation>(next_level_prolongation(h, 0)),
       std::make_shared<const ShellProlongation>(next_level_prolongation(h, 1))},
      std::move(finest), std::vector<std::unique_ptr<EnergyTerm>>{});
  Vector x = as_dofs(h.levels[0].rest.vertices);
  for (int v = 0; v < h.levels[0].rest.num_vertices(); ++v) x[3 * v + 2] = 0.01 * (v % 7);
  Vector g = Vector::Zero(x.size());
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    proxy.add_gradient(x, g);  // warm-up: OpenMP's thread team and the Jacobian workspaces
    const long count = allocations_in([&] {
      for (int k = 0; k < 10; ++k) {
        proxy.value(x);
        proxy.add_gradient(x, g);
      }
    });
    EXPECT_EQ(count, 0) << threads << " thread(s)";
  }
}

/// The mid-edge terms' per-face evaluation (PSD clamp included) on 1 and 2 threads.
template <class Term>
void expect_allocation_free_bending() {
  const TriangleMesh sheet = make_grid(1.0, 1.0, 20, 20);
  const Term term(sheet.vertices, sheet.faces,
                  build_topology(sheet.faces, sheet.num_vertices()).hinges,
                  std::vector<ShellMaterial>(sheet.num_faces()));
  Vector x = as_dofs(sheet.vertices);
  for (int v = 0; v < sheet.num_vertices(); ++v) x[3 * v + 2] = 0.01 * (v % 7);
  Vector g = Vector::Zero(x.size());
  std::vector<double> values(term.hessian_entry_count());
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    term.add_gradient(x, g);  // warm-up: OpenMP's thread team
    const long count = allocations_in([&] {
      term.value(x);
      term.add_gradient(x, g);
      term.hessian_values(x, true, values.data());
      term.hessian_values(x, false, values.data());
    });
    EXPECT_EQ(count, 0) << threads << " thread(s)";
  }
}

TEST(AllocationFree, MidedgeBendingValueGradientAndHessian) {
  expect_allocation_free_bending<MidedgeBending>();  // 18-DOF elements
}

TEST(AllocationFree, FittedMidedgeBendingValueGradientAndHessian) {
  expect_allocation_free_bending<FittedMidedgeBending>();  // 36-DOF elements
}

TEST(AllocationFree, ContactBarrierWithinOneContactSet) {
  // Two 3721-vertex sheets 4 mm apart (d̂ = 1 cm): every top vertex is in contact. Once the
  // Hessian's pattern holds the contact set, a Newton iteration's value, gradient and assembled
  // Hessian at a new x allocate nothing (the membrane keeps the sheets' Hessian non-trivial).
  const TriangleMesh sheet = make_grid(1.0, 1.0, 60, 60);
  const int n = sheet.num_vertices();
  const TriangleMesh two = test_support::stacked_sheets(sheet, sheet, 0.004);
  Problem problem(3 * 2 * n);
  problem.add_term(std::make_unique<NeoHookeanMembrane>(
      two.vertices, two.faces, std::vector<ShellMaterial>(two.num_faces())));
  const ContactPotential& contact = problem.add_term(std::make_unique<ContactPotential>(
      build_collision_mesh(two.vertices, two.faces, std::vector<double>(2 * n, 0.0),
                           std::vector<double>(2 * n, 0.0), {}),
      0.01, 1.0, std::nullopt));
  problem.finalize();
  const Vector x = as_dofs(two.vertices);
  Vector shifted = x;
  for (int v = n; v < 2 * n; ++v) shifted[3 * v] += 1e-5 * (v % 3);  // the same contact set
  const Vector* const iterates[] = {&x, &shifted, &x};
  Vector g = Vector::Zero(x.size());
  problem.begin_solve(x);
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    for (const Vector* at : iterates) {  // warm-up: buffers and the Hessian's pattern
      problem.value(*at);
      problem.gradient(*at, g);
      problem.hessian(*at, true);
    }
    const long version = problem.pattern_version();
    const long count = allocations_in([&] {
      for (const Vector* at : iterates) {
        problem.value(*at);
        problem.gradient(*at, g);
        problem.hessian(*at, true);
        problem.hessian(*at, false);
      }
    });
    EXPECT_EQ(count, 0) << threads << " thread(s)";
    EXPECT_EQ(problem.pattern_version(), version) << "the contact set was meant to stay";
    EXPECT_GT(contact.stats().active_pairs, 2 * n) << "the sheets were meant to touch";
  }
}

}  // namespace
