// The proxy shell energy Ψ_L(P^l(x)) of PSQ eq. 2: its gradient against central finite
// differences of its value, its value at rest against the finest level's own, and its Hessian
// against the level's own shell Hessian (the preconditioner of PSQ Algorithm 1).
#include <gtest/gtest.h>
#include <omp.h>

#include "common/error.hpp"
#include "energy/gravity.hpp"
#include "energy/hinge_bending.hpp"
#include "energy/lumped_mass.hpp"
#include "energy/neo_hookean_membrane.hpp"
#include "energy/prolonged_elastics.hpp"
#include "hierarchy/hierarchy_test_meshes.hpp"
#include "hierarchy/level_prolongation.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/mesh_topology.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

/// Membrane, bending and gravity on `mesh` with per-face materials from `seed`.
std::vector<std::unique_ptr<EnergyTerm>> shell_terms(const TriangleMesh& mesh, bool gravity) {
  const std::vector<ShellMaterial> materials = varied_materials(mesh.num_faces(), 7);
  std::vector<std::unique_ptr<EnergyTerm>> terms;
  terms.push_back(std::make_unique<NeoHookeanMembrane>(mesh.vertices, mesh.faces, materials));
  terms.push_back(std::make_unique<HingeBending>(
      mesh.vertices, mesh.faces, build_topology(mesh.faces, mesh.num_vertices()).hinges,
      materials));
  if (gravity)
    terms.push_back(std::make_unique<Gravity>(
        lumped_vertex_masses(mesh.vertices, mesh.faces, materials), Vec3(0.3, -9.81, 0.5)));
  return terms;
}

/// dome(9) with coarse levels of 20 and 50 vertices, and its per-level prolongations.
struct DomeChain {
  TriangleMesh mesh = dome(9);
  MeshHierarchy hierarchy = build_hierarchy(mesh, options());
  std::vector<std::shared_ptr<const ShellProlongation>> chain = {
      std::make_shared<const ShellProlongation>(next_level_prolongation(hierarchy, 0)),
      std::make_shared<const ShellProlongation>(next_level_prolongation(hierarchy, 1))};

  static HierarchyOptions options() {
    HierarchyOptions o;
    o.coarse_vertex_counts = {20, 50};
    return o;
  }
};

struct ProxyCase {
  MeshHierarchy hierarchy;
  std::shared_ptr<const ShellProlongation> to_finest;
  std::unique_ptr<ProlongedElastics> proxy;

  ProxyCase(const TriangleMesh& mesh, int coarse_vertices) {
    HierarchyOptions options;
    options.coarse_vertex_counts = {coarse_vertices};
    hierarchy = build_hierarchy(mesh, options);
    to_finest = std::make_shared<const ShellProlongation>(direct_prolongation(hierarchy, 0));
    proxy = std::make_unique<ProlongedElastics>(to_finest, shell_terms(mesh, true),
                                                shell_terms(coarse(), false));
  }
  const TriangleMesh& coarse() const { return hierarchy.levels[0].rest; }
};

}  // namespace

TEST(ProlongedElastics, GradientMatchesFiniteDifferencesOnACurvedShell) {
  const ProxyCase c(dome(12), 40);
  for (unsigned seed : {1u, 2u}) {
    const Vector x = perturbed(c.coarse().vertices, 0.03, seed);
    const Vector analytic = analytic_gradient(*c.proxy, x);
    const Vector numeric = finite_difference_gradient(*c.proxy, x, 1e-6);
    EXPECT_LT(relative_error(analytic, numeric, 1e-3), 1e-5) << "seed " << seed;
  }
}

TEST(ProlongedElastics, GradientMatchesFiniteDifferencesWithARollerPinnedCoordinate) {
  // A roller holds one coordinate of a finest vertex: that coordinate stops depending on x,
  // the other two stay prolonged.
  const ProxyCase c(dome(12), 40);
  const int vertex = 7;
  c.proxy->pin_finest_dofs({3 * vertex + 2}, Vector::Constant(1, 0.05));
  const Vector x = perturbed(c.coarse().vertices, 0.03, 3);
  const Vector analytic = analytic_gradient(*c.proxy, x);
  const Vector numeric = finite_difference_gradient(*c.proxy, x, 1e-6);
  EXPECT_LT(relative_error(analytic, numeric, 1e-3), 1e-5);
  EXPECT_EQ(c.proxy->last_prolonged()(vertex, 2), 0.05);
  const Positions free_prolonged = c.proxy->last_prolonged();
  c.proxy->pin_finest_dofs({}, Vector());
  c.proxy->value(x);
  EXPECT_NE(c.proxy->last_prolonged()(vertex, 2), 0.05);
  EXPECT_EQ(c.proxy->last_prolonged().row(vertex).head<2>(), free_prolonged.row(vertex).head<2>());
}

TEST(ProlongedElastics, ValueAtRestIsTheFinestValueAtRest) {
  const TriangleMesh mesh = dome(12);
  const ProxyCase c(mesh, 40);
  double finest = 0.0;
  for (const auto& term : shell_terms(mesh, true)) finest += term->value(as_dofs(mesh.vertices));
  const double proxy = c.proxy->value(as_dofs(c.coarse().vertices));
  EXPECT_NEAR(proxy, finest, 1e-10 * std::abs(finest));
  EXPECT_LT((c.proxy->last_prolonged() - mesh.vertices).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ProlongedElastics, OnAFlatSheetTheGradientIsTheRestrictedFineGradient) {
  // A flat rest sheet has no offsets (a ≡ 0), so J = U and the gradient is Uᵀ∇Ψ_L(Ux).
  const TriangleMesh mesh = make_grid(1.0, 1.0, 14, 14);
  const ProxyCase c(mesh, 50);
  const Vector x = perturbed(c.coarse().vertices, 0.05, 3);
  const Positions fine = c.to_finest->intrinsic() * as_positions(x);
  Vector fine_gradient = Vector::Zero(3 * mesh.num_vertices());
  for (const auto& term : shell_terms(mesh, true)) term->add_gradient(as_dofs(fine), fine_gradient);
  const Positions restricted = c.to_finest->restrict_gradient(as_positions(fine_gradient));
  EXPECT_LT(relative_error(analytic_gradient(*c.proxy, x), as_dofs(restricted), 1e-3), 1e-10);
}

TEST(ProlongedElastics, HessianIsTheLevelsOwnShellHessian) {
  const ProxyCase c(dome(10), 30);
  const Vector x = perturbed(c.coarse().vertices, 0.02, 4);
  Eigen::MatrixXd own = Eigen::MatrixXd::Zero(x.size(), x.size());
  for (const auto& term : shell_terms(c.coarse(), false)) own += assembled_hessian(*term, x, true);
  EXPECT_LT(relative_error(assembled_hessian(*c.proxy, x, true), own, 1e-6), 1e-12);
}

TEST(ProlongedElastics, CountsFinestEvaluationsAndRejectsWrongSizes) {
  const ProxyCase c(dome(8), 20);
  const Vector x = as_dofs(c.coarse().vertices);
  Vector g = Vector::Zero(x.size());
  c.proxy->value(x);
  c.proxy->add_gradient(x, g);
  const std::vector<TermStats> stats = c.proxy->finest_term_stats();
  ASSERT_EQ(stats.size(), 3u);
  EXPECT_EQ(stats[0].name, "membrane@finest");
  EXPECT_EQ(stats[0].value_evaluations, 1);
  EXPECT_EQ(stats[0].gradient_evaluations, 1);
  EXPECT_THROW(c.proxy->value(Vector::Zero(x.size() + 3)), Error);
}

TEST(ProlongedElastics, GalerkinHessianIsTheFinestHessianProjectedByU) {
  // Independent reference: dense U (the product of the per-level intrinsic matrices) and the
  // finest terms' own Hessian at P(x), with a pinned finest vertex's rows and columns removed.
  const DomeChain dome_chain;
  const TriangleMesh& mesh = dome_chain.mesh;
  const MeshHierarchy& h = dome_chain.hierarchy;
  const auto& chain = dome_chain.chain;
  ProlongedElastics proxy(chain, shell_terms(mesh, true), mesh.vertices);
  proxy.pin_finest_dofs({15, 16, 17}, mesh.vertices.row(5).transpose());
  const Vector x = perturbed(h.levels[0].rest.vertices, 0.02, 6);
  const Eigen::MatrixXd u =
      Eigen::MatrixXd(chain[1]->intrinsic()) * Eigen::MatrixXd(chain[0]->intrinsic());
  Eigen::MatrixXd lift = Eigen::MatrixXd::Zero(3 * u.rows(), 3 * u.cols());
  for (int i = 0; i < u.rows(); ++i)
    for (int j = 0; j < u.cols(); ++j) lift.block<3, 3>(3 * i, 3 * j) = u(i, j) * Mat3::Identity();
  const Eigen::MatrixXd full_lift = lift;
  lift.middleRows<3>(15).setZero();  // vertex 5 is pinned
  proxy.value(x);
  const Vector fine = as_dofs(proxy.last_prolonged());
  Eigen::MatrixXd fine_hessian = Eigen::MatrixXd::Zero(fine.size(), fine.size());
  for (const auto& term : shell_terms(mesh, true))
    fine_hessian += assembled_hessian(*term, fine, true);
  const Eigen::MatrixXd expected = lift.transpose() * fine_hessian * lift;
  EXPECT_LT(relative_error(assembled_hessian(proxy, x, true), expected, 1e-6), 1e-10);

  proxy.pin_finest_dofs({16}, Vector::Constant(1, mesh.vertices(5, 1)));  // a roller: y only
  lift = full_lift;
  lift.row(16).setZero();
  proxy.value(x);
  const Vector rolled = as_dofs(proxy.last_prolonged());
  Eigen::MatrixXd rolled_hessian = Eigen::MatrixXd::Zero(rolled.size(), rolled.size());
  for (const auto& term : shell_terms(mesh, true))
    rolled_hessian += assembled_hessian(*term, rolled, true);
  EXPECT_LT(relative_error(assembled_hessian(proxy, x, true),
                           lift.transpose() * rolled_hessian * lift, 1e-6),
            1e-10);
}

TEST(ProlongedElastics, GalerkinHessianIsTheSameOnOneAndTwoThreads) {
  // Each coarse column is summed by one thread in a fixed order, so the team's size cannot
  // change a bit of the matrix (a run must not depend on the cores it was given).
  const DomeChain dome_chain;
  const auto& chain = dome_chain.chain;
  ProlongedElastics proxy(chain, shell_terms(dome_chain.mesh, true), dome_chain.mesh.vertices);
  proxy.pin_finest_dofs({15, 16, 17}, dome_chain.mesh.vertices.row(5).transpose());
  const Vector x = perturbed(dome_chain.hierarchy.levels[0].rest.vertices, 0.02, 3);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Eigen::MatrixXd one = assembled_hessian(proxy, x, true);
  omp_set_num_threads(2);
  const Eigen::MatrixXd two = assembled_hessian(proxy, x, true);
  omp_set_num_threads(threads);
  EXPECT_GT(one.norm(), 0.0);
  EXPECT_EQ(one, two);
}

TEST(ProlongedElastics, GalerkinHessianIsReassembledOnlyBeyondTheRefreshDistance) {
  // A chord method's contract: the matrix is the last assembly's while the finest state has
  // moved, net of its mean translation, by at most the refresh distance at every vertex; past
  // it (a rotation, a NaN, another pinned set) it is the exact Uᵀ H U again, as a proxy that
  // assembles every time (checked against a dense reference above) computes it.
  const DomeChain dome_chain;
  const TriangleMesh& mesh = dome_chain.mesh;
  const MeshHierarchy& h = dome_chain.hierarchy;
  const auto& chain = dome_chain.chain;
  const double refresh = 0.05;
  ProlongedElastics lazy(chain, shell_terms(mesh, false), mesh.vertices, refresh);
  ProlongedElastics exact(chain, shell_terms(mesh, false), mesh.vertices);
  const std::int64_t at_construction = lazy.finest_term_stats()[0].hessian_evaluations;  // pattern
  const auto assemblies = [&] {
    return lazy.finest_term_stats()[0].hessian_evaluations - at_construction;
  };
  const Positions coarse = h.levels[0].rest.vertices;
  const Vector x = perturbed(coarse, 0.02, 6);
  const Eigen::MatrixXd first = assembled_hessian(lazy, x, true);
  EXPECT_EQ(assemblies(), 1);

  Positions moved = as_positions(x);
  moved.rowwise() += Eigen::RowVector3d(3.0, -2.0, 0.5);  // far, but a translation
  moved(0, 1) += 0.4 * refresh;                           // and one vertex a little
  EXPECT_EQ(assembled_hessian(lazy, as_dofs(moved), true), first);
  EXPECT_EQ(assemblies(), 1);

  const Mat3 turn = Eigen::AngleAxisd(0.5, Vec3::UnitY()).toRotationMatrix();
  const Vector rotated = as_dofs(Positions(as_positions(x) * turn.transpose()));
  const Eigen::MatrixXd after_turn = assembled_hessian(lazy, rotated, true);
  EXPECT_EQ(assemblies(), 2);
  EXPECT_LT(relative_error(after_turn, assembled_hessian(exact, rotated, true), 1e-6), 1e-12);
  EXPECT_GT(relative_error(after_turn, first, 1e-6), 1e-2);

  assembled_hessian(lazy, rotated, false);  // another projection
  EXPECT_EQ(assemblies(), 3);
  lazy.pin_finest_dofs({15, 16, 17}, mesh.vertices.row(5).transpose());  // another pinned set
  assembled_hessian(lazy, rotated, false);
  EXPECT_EQ(assemblies(), 4);
  Vector broken = rotated;
  broken[4] = std::numeric_limits<double>::quiet_NaN();
  assembled_hessian(lazy, broken, false);
  EXPECT_EQ(assemblies(), 5);

  EXPECT_THROW(ProlongedElastics(chain, shell_terms(mesh, false), mesh.vertices, -1.0), Error);
}
