// The exact chain rule through the shell prolongation: Jᵀg from add_jacobian_transpose against
// central finite differences of ⟨G, P(x)⟩, on a curved (dome) and a flat hierarchy at deformed
// states.
#include <gtest/gtest.h>

#include <random>

#include "hierarchy/hierarchy_test_meshes.hpp"
#include "hierarchy/level_prolongation.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/mesh_generators.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

TEST(ShellProlongationJacobian, MatchesFiniteDifferences) {
  for (const TriangleMesh& mesh : {dome(16), make_grid(1.0, 1.0, 16, 16)}) {
    HierarchyOptions options;
    options.coarse_vertex_counts = {40};
    const MeshHierarchy h = build_hierarchy(mesh, options);
    const ShellProlongation p = direct_prolongation(h, 0);
    std::mt19937 rng(5);
    std::normal_distribution<double> normal;
    Positions x = h.levels[0].rest.vertices;
    for (int i = 0; i < x.rows(); ++i)
      x.row(i) += 0.03 * Eigen::RowVector3d(normal(rng), normal(rng), normal(rng));
    Positions g(mesh.num_vertices(), 3);
    for (int i = 0; i < g.rows(); ++i) g.row(i) << normal(rng), normal(rng), normal(rng);
    Positions analytic = Positions::Zero(x.rows(), 3);
    std::vector<Eigen::Matrix<double, 9, 1>> workspace;
    p.add_jacobian_transpose(x, g, analytic, workspace);
    const double step = 1e-6;
    double worst = 0.0;
    for (int i = 0; i < x.rows(); ++i)
      for (int k = 0; k < 3; ++k) {
        Positions plus = x, minus = x;
        plus(i, k) += step;
        minus(i, k) -= step;
        const double fd = ((p(plus) - p(minus)).cwiseProduct(g)).sum() / (2 * step);
        worst = std::max(worst, std::abs(fd - analytic(i, k)) / (1.0 + std::abs(fd)));
      }
    EXPECT_LT(worst, 1e-6);
    std::printf("worst relative difference %.2e\n", worst);
  }
}

}  // namespace
