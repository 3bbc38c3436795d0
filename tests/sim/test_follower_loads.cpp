// Follower loads (issue 30 §2): a normal force that turns with the surface, against the
// elastica of a cantilever under an end load that stays normal to its free end, computed
// independently by tests/data/elastica.py.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "energy/follower_loads.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "sim/load_forces.hpp"
#include "support/energy_checks.hpp"
#include "support/expect_error.hpp"
#include "support/sze_strip.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

/// Sze's strip (support/sze_strip.hpp) with nx cells along, clamped on its first two columns
/// at x = ∓a/2 (mid-edge bending holds the rotation at x = 0, see
/// test_bending_convergence.cpp), its end column at x = L carrying a normal force ramped to
/// k_max E I / L² over 4 steps.
Scene follower_cantilever(int nx, double k_max) {
  const double a = kSzeLength / (nx - 0.5);
  Scene scene =
      sze_strip_scene("follower_cantilever", -0.5 * a, kSzeLength, nx, BendingModel::midedge, 0.25);
  Handle clamp;
  clamp.vertices = sze_vertices_below(scene, a);
  Load end;
  end.normal_force = k_max * kSzeBendingStiffness / (kSzeLength * kSzeLength);
  end.distribution = LoadDistribution::area;
  end.ramp = 1.0;
  end.vertices = sze_vertices_above(scene, kSzeLength - 1e-9);
  scene.handles.push_back(clamp);
  scene.loads.push_back(end);
  return scene;
}

/// (−u / L, w / L) of the end column's mean displacement.
Eigen::Vector2d tip_over_length(const LevelSimulation& sim, const Scene& scene) {
  Vec3 sum = Vec3::Zero();
  for (int v : scene.loads[0].vertices)
    sum += (sim.positions().row(v) - scene.bodies[0].mesh.vertices.row(v)).transpose();
  sum /= static_cast<double>(scene.loads[0].vertices.size());
  return Eigen::Vector2d(-sum.x(), sum.z()) / kSzeLength;
}

}  // namespace

TEST(FollowerLoads, CantileverUnderAnEndLoadNormalToItMatchesTheElastica) {
  // Elastica θ'' = −k cos(θ − θ_L), θ(0) = 0, θ'(1) = 0 (tests/data/elastica.py,
  // RK4 shooting): (−u/L, w/L) = (0.06435, 0.32064), (0.23264, 0.57384), (0.65725, 0.78617) at
  // k = P L²/E I = 1, 2, 4. A dead load of the same size gives (0.32894, 0.66996) at k = 4
  // (Sze 3.1), so the test tells a follower from a dead load. Measured: largest error (of L)
  // 3.7e-3, 1.0e-3, 3.6e-4 at nx = 20, 40, 80 (first order, the end cell's normal lags the end's
  // tangent by half a cell); 4, 4 and 7 relaxed re-aims per step at k = 1, 2, 4 (plain lagging
  // contracted by 0.04, 0.18 and 0.47 per re-aim at k = 1, 2, 3 and did not settle in 50 at 4).
  const double reference[3][2] = {{0.06435, 0.32064}, {0.23264, 0.57384}, {0.65725, 0.78617}};
  const int check_step[3] = {1, 2, 4};  // k = 1, 2, 4 of the ramp to 4
  std::printf("[ follower ] %4s %4s %9s %9s %9s %9s %5s\n", "nx", "k", "-u/L", "ref", "w/L", "ref",
              "lags");
  double previous_error = 1.0;
  for (int nx : {20, 40, 80}) {
    const Scene scene = follower_cantilever(nx, 4.0);
    LevelSimulation sim(scene);
    double worst = 0.0;
    for (int step = 1, checked = 0; step <= 4; ++step) {
      const StepRecord r = sim.step();
      ASSERT_EQ(r.newton.stop, NewtonStop::converged)
          << "nx " << nx << " step " << step << ": " << stop_name(r.newton.stop) << " after "
          << r.newton.iterations << " iterations, " << r.follower_lags.value_or(-1) << " lags";
      ASSERT_TRUE(r.follower_lags.has_value());
      EXPECT_LT(*r.follower_lags, 50) << "the directions settled";
      if (step != check_step[checked]) continue;
      const Eigen::Vector2d tip = tip_over_length(sim, scene);
      std::printf("[ follower ] %4d %4d %9.5f %9.5f %9.5f %9.5f %5d\n", nx, step, tip[0],
                  reference[checked][0], tip[1], reference[checked][1], *r.follower_lags);
      worst = std::max({worst, std::abs(tip[0] - reference[checked][0]),
                        std::abs(tip[1] - reference[checked][1])});
      ++checked;
    }
    EXPECT_LT(worst, previous_error) << "nx = " << nx << ": converges under refinement";
    if (nx >= 40) EXPECT_LT(worst, 0.01) << "nx = " << nx << " (of L)";
    previous_error = worst;
  }
}

TEST(FollowerLoads, ExistOnlyInScenesThatAskAndAreCheckedOnTheWay) {
  Scene scene = follower_cantilever(20, 1.0);
  {
    LevelSimulation sim(scene);
    ASSERT_NE(sim.problem().find_term("follower_loads"), nullptr);
  }
  scene.loads[0].normal_force = 0.0;
  scene.loads[0].force = Vec3(0, 0, 0.01);
  LevelSimulation dead(scene);
  EXPECT_EQ(dead.problem().find_term("follower_loads"), nullptr) << "no normal force, no term";
  EXPECT_FALSE(dead.step().follower_lags.has_value());
  scene.loads[0].normal_force = std::nan("");
  expect_error([&] { validate_scene(scene); }, Status::invalid_scene,
               {"loads[0].normal_force", "non-finite"});
  scene.loads[0].normal_force = 1.0;
  scene.progressive.level_vertices = {50};
  expect_error([&] { validate_scene(scene); }, Status::unsupported,
               {"loads[0].normal_force", "direct simulation"});
  const Scene parsed = parse_scene(R"({"simulation": {"mode": "quasistatic"},
      "effects": ["membrane"], "bodies": [{"name": "s", "mesh": {"generator": "grid",
      "width": 1, "height": 1, "nx": 2, "ny": 2}}],
      "loads": [{"body": "s", "vertices": [2], "normal_force": -3, "distribution": "per_vertex"}]})",
                                   ".");
  EXPECT_EQ(parsed.loads[0].normal_force, -3.0);
}

TEST(FollowerLoads, AimTurnsTheForcesAlongTheUnitVertexNormals) {
  // A unit square (two faces, normal +z) turned by 90° about x: the normal becomes −y. The
  // potential's gradient is −a n̄ at each loaded vertex; aim() reports the turn (π/2).
  const TriangleMesh mesh = make_grid(1.0, 1.0, 1, 1);
  NormalLoad load{{0, 3}, Eigen::Vector2d(2.0, 5.0)};
  FollowerLoads term({load}, mesh.faces, 4);
  Vector x = as_dofs(mesh.vertices);
  EXPECT_DOUBLE_EQ(term.aim(x), 3.141592653589793);  // the first lag
  Vector g = Vector::Zero(12);
  term.add_gradient(x, g);
  EXPECT_LT((g.segment<3>(0) - Vec3(0, 0, -2.0)).norm(), 1e-15);
  EXPECT_LT((g.segment<3>(9) - Vec3(0, 0, -5.0)).norm(), 1e-15);
  for (int v = 0; v < 4; ++v) {  // turned 90° about x: (x, y, z) → (x, −z, y), so +z → −y
    const Vec3 p = x.segment<3>(3 * v);
    x.segment<3>(3 * v) = Vec3(p.x(), -p.z(), p.y());
  }
  EXPECT_NEAR(term.aim(x), 0.5 * 3.141592653589793, 1e-12);
  g.setZero();
  term.add_gradient(x, g);  // −a n̄ with n̄ = −y
  EXPECT_LT((g.segment<3>(0) - Vec3(0, 2.0, 0)).norm(), 1e-15);
  EXPECT_LT((g.segment<3>(9) - Vec3(0, 5.0, 0)).norm(), 1e-15);
  EXPECT_EQ(g.segment<6>(3).norm(), 0.0) << "unloaded vertices";
  EXPECT_DOUBLE_EQ(term.aim(x), 0.0) << "no turn since the last aim";
}

TEST(FollowerLoads, DerivativesMatchFiniteDifferencesAndTheMagnitudesSumToTheLoad) {
  // Within a solve the lagged potential −Σ s a n·x is linear: its gradient against central
  // differences, no Hessian entries; the normal force spread by area or mass sums to N.
  Scene scene = follower_cantilever(20, 2.0);
  const ShellModel model = build_shell_model(scene);
  for (LoadDistribution d : {LoadDistribution::area, LoadDistribution::mass}) {
    scene.loads[0].distribution = d;
    const std::vector<NormalLoad> loads = normal_loads(scene, model);
    ASSERT_EQ(loads.size(), 1u);
    EXPECT_NEAR(loads[0].magnitudes.sum(), scene.loads[0].normal_force,
                1e-14 * scene.loads[0].normal_force);
    FollowerLoads term(loads, model.rest.faces, model.rest.num_vertices());
    term.aim(perturbed(model.rest.vertices, 0.05, 7));  // aimed at one state ...
    term.set_factor(0, 0.6);
    const Vector x = perturbed(model.rest.vertices, 0.05, 8);  // ... differentiated at another
    expect_derivatives_match_finite_differences(term, x, 1e-6, 1e-8, 1e-9);
    EXPECT_EQ(term.hessian_entry_count(), 0u);
  }
}
