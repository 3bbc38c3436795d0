// DeadLoads and the forces of point/line loads: derivatives against finite differences for
// every kind of load, totals against the requested force, and couples against their moment.
#include <gtest/gtest.h>

#include <random>

#include "energy/dead_loads.hpp"
#include "energy/force_couple.hpp"
#include "energy/lumped_mass.hpp"
#include "mesh/mesh_generators.hpp"
#include "sim/load_forces.hpp"
#include "support/energy_checks.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
namespace pt = progsim::test_support;

namespace {

/// A 0.6 m × 0.4 m sheet of 4 × 3 quads, bent a little out of its plane, as one body, so that
/// lumped masses and areas differ from vertex to vertex.
Scene load_test_scene() {
  Scene scene;
  TriangleMesh sheet = make_grid(0.6, 0.4, 4, 3);
  for (Eigen::Index i = 0; i < sheet.vertices.rows(); ++i)
    sheet.vertices(i, 2) = 0.1 * sheet.vertices(i, 0) * sheet.vertices(i, 0);
  scene.bodies.push_back({"sheet", sheet, {}, 0.0, 0.0});
  return scene;
}

/// The scene's one load of the given kind on vertices {1, 6, 7, 12, 18}.
Scene scene_with_load(LoadDistribution distribution, double moment) {
  Scene scene = load_test_scene();
  Load load;
  load.vertices = {1, 6, 7, 12, 18};
  load.force = Vec3(0.3, -2.0, 0.7);
  load.distribution = distribution;
  load.moment_axis = Vec3(0.2, 0.3, 1.0);
  load.moment = moment;
  scene.loads.push_back(load);
  return scene;
}

/// The moment Σ (p_i − o) × f_i (N·m) of forces at points about o.
Vec3 moment_about(const Positions& points, const Positions& forces, const Vec3& o) {
  Vec3 m = Vec3::Zero();
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    m += (points.row(i).transpose() - o).cross(forces.row(i).transpose());
  return m;
}

}  // namespace

TEST(DeadLoads, DerivativesMatchFiniteDifferencesForEveryKindOfLoad) {
  for (LoadDistribution d :
       {LoadDistribution::mass, LoadDistribution::area, LoadDistribution::per_vertex}) {
    for (double moment : {0.0, 1.5}) {
      const Scene scene = scene_with_load(d, moment);
      const ShellModel model = build_shell_model(scene);
      DeadLoads term(load_forces(scene, model), model.rest.num_vertices());
      term.set_factor(0, 0.7);
      EXPECT_STREQ(term.name(), "loads");
      const Vector x = pt::perturbed(model.rest.vertices, 0.05, 4);
      pt::expect_derivatives_match_finite_differences(term, x, 1e-6, 1e-8, 1e-9);
      EXPECT_EQ(term.hessian_entry_count(), 0u);  // linear: E = −s Σ f·x
    }
  }
}

TEST(DeadLoads, ValueIsMinusTheWorkOfTheScaledForces) {
  VertexForces load{{0, 2}, Positions(2, 3)};
  load.forces << 1.0, 2.0, 3.0, -4.0, 0.5, 0.0;
  DeadLoads term({load}, 3);
  term.set_factor(0, 0.5);
  Vector x(9);
  x << 1, 1, 1, 9, 9, 9, 2, -1, 4;
  EXPECT_DOUBLE_EQ(term.value(x), -0.5 * ((1 + 2 + 3) + (-8 - 0.5)));
  EXPECT_EQ(term.total_force(), Vec3(-1.5, 1.25, 1.5));
  pt::expect_error([&] { DeadLoads({load}, 2); }, Status::invalid_argument, {"vertex 2"});
}

TEST(DeadLoads, MassAndAreaDistributionsSumToTheRequestedForce) {
  for (LoadDistribution d : {LoadDistribution::mass, LoadDistribution::area}) {
    const Scene scene = scene_with_load(d, 0.0);
    const ShellModel model = build_shell_model(scene);
    const std::vector<VertexForces> forces = load_forces(scene, model);
    ASSERT_EQ(forces.size(), 1u);
    const Vec3 total = forces[0].forces.colwise().sum().transpose();
    EXPECT_LT((total - scene.loads[0].force).norm(), 1e-15 * 8) << total.transpose();
    // Each share is proportional to its weight: compare two vertices' ratio.
    const Eigen::VectorXd w = d == LoadDistribution::mass
                                  ? model.vertex_masses
                                  : lumped_vertex_areas(model.rest.vertices, model.rest.faces);
    const std::vector<int>& v = forces[0].vertices;
    EXPECT_NEAR(forces[0].forces(0, 1) / forces[0].forces(3, 1), w[v[0]] / w[v[3]], 1e-14);
  }
  const Scene each = scene_with_load(LoadDistribution::per_vertex, 0.0);
  const std::vector<VertexForces> per_vertex = load_forces(each, build_shell_model(each));
  for (Eigen::Index j = 0; j < per_vertex[0].forces.rows(); ++j)
    EXPECT_EQ(Vec3(per_vertex[0].forces.row(j)), each.loads[0].force);
}

TEST(DeadLoads, LumpedAreasSumToTheMeshArea) {
  const TriangleMesh sheet = make_grid(0.6, 0.4, 4, 3);
  const Eigen::VectorXd areas = lumped_vertex_areas(sheet.vertices, sheet.faces);
  EXPECT_NEAR(areas.sum(), 0.24, 1e-15);
  // Masses of a unit areal density (ρ t = 1 kg/m²) are the areas.
  ShellMaterial unit;
  unit.density = 1000.0;
  unit.thickness = 1e-3;
  const std::vector<ShellMaterial> materials(sheet.num_faces(), unit);
  EXPECT_LT((areas - lumped_vertex_masses(sheet.vertices, sheet.faces, materials)).norm(), 1e-16);
}

TEST(DeadLoads, CoupleHasZeroNetForceAndTheMomentAboutItsAxisForAnyGroup) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const int k = 3 + trial % 6;  // not on one line (two points carry no twist about their line)
    Positions points(k, 3);
    Eigen::VectorXd weights(k);
    for (int i = 0; i < k; ++i) {
      points.row(i) << uniform(rng), uniform(rng), uniform(rng);
      weights[i] = 1.5 + uniform(rng);
    }
    const Vec3 axis(uniform(rng), uniform(rng), uniform(rng));
    const double m = 10.0 * uniform(rng);
    const Positions f = couple_forces(points, weights, axis, m, "test");
    const double scale = f.cwiseAbs().maxCoeff();
    EXPECT_LT(f.colwise().sum().norm(), 1e-14 * scale) << "trial " << trial;
    for (const Vec3& o : {Vec3(Vec3::Zero()), Vec3(3.0, -2.0, 5.0)})  // Σf = 0: any point
      EXPECT_LT((moment_about(points, f, o) - m * axis.normalized()).norm(), 1e-13 * (1 + scale))
          << "trial " << trial;
  }
}

TEST(DeadLoads, PlanarCoupleIsTheBoltGroupDistribution) {
  // Points in a plane normal to a: f_i = M w_i a × r_i / Σ w_j |r_j|² (Shigley eq. 8-57).
  Positions points(3, 3);
  points << 0, 0, 2, 1, 0, 2, 0, 3, 2;
  const Eigen::Vector3d w(1.0, 2.0, 3.0);
  const Vec3 a = Vec3::UnitZ();
  const Positions f = couple_forces(points, w, 2.0 * a, 6.0, "test");
  const Vec3 c = (w.transpose() * points).transpose() / w.sum();
  double j = 0.0;
  for (int i = 0; i < 3; ++i) j += w[i] * (points.row(i).transpose() - c).squaredNorm();
  for (int i = 0; i < 3; ++i) {
    const Vec3 expected = 6.0 * w[i] * a.cross(points.row(i).transpose() - c) / j;
    EXPECT_LT((f.row(i).transpose() - expected).norm(), 1e-14) << i;
  }
}

TEST(DeadLoads, CoupleOnALineAlongItsAxisIsRefused) {
  Positions line(3, 3);
  line << 0, 0, 0, 0, 1, 0, 0, 2, 0;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(3);
  pt::expect_error([&] { couple_forces(line, ones, Vec3::UnitY(), 1.0, "loads[2].moment"); },
                   Status::invalid_scene, {"loads[2].moment", "one line"});
  // About an axis across the line, the line carries it (a bending couple on an edge).
  const Positions f = couple_forces(line, ones, Vec3::UnitX(), 1.0, "test");
  EXPECT_LT((moment_about(line, f, Vec3::Zero()) - Vec3::UnitX()).norm(), 1e-14);
  EXPECT_TRUE(couple_forces(line, ones, Vec3::UnitY(), 0.0, "test").isZero(0.0));
}
