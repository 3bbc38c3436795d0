// Progressive Shell Quasistatics without contact (PSQ §3, Algorithm 1): preview at a coarse
// level with the proxy energy, refinement level by level, the finest level to convergence.
#include <gtest/gtest.h>

#include <iostream>

#include "common/error.hpp"
#include "progressive/progressive_simulation.hpp"
#include "progressive/progressive_test_scenes.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

/// RMS and max vertex distance between two states, over the bounding-box diagonal of `rest`.
std::pair<double, double> relative_distance(const Positions& a, const Positions& b,
                                            const Positions& rest) {
  const Eigen::VectorXd d = (a - b).rowwise().norm();
  const double diagonal = (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm();
  return {std::sqrt(d.squaredNorm() / d.size()) / diagonal, d.maxCoeff() / diagonal};
}

}  // namespace

class ProxyProlongations : public ::testing::TestWithParam<ProxyProlongation> {};
INSTANTIATE_TEST_SUITE_P(ProgressiveSimulation, ProxyProlongations,
                         ::testing::Values(ProxyProlongation::composed, ProxyProlongation::direct));

TEST_P(ProxyProlongations, RefinedToTheFinestLevelItReachesTheDirectSolution) {
  Scene scene = curved_cantilever(16, 40);  // 697 vertices
  scene.progressive.level_vertices = {60, 200};
  scene.progressive.prolongation = GetParam();
  scene.progressive.preview_tolerance = 1e-5;
  scene.solver.tolerance = 1e-9;  // both finest solves converge far below the sag
  ProgressiveSimulation psq(scene);
  psq.step();
  ASSERT_TRUE(psq.settle_to_equilibrium(300));
  while (psq.level() < psq.finest()) {
    psq.refine();
    ASSERT_TRUE(psq.settle_to_equilibrium(300)) << "level " << psq.level();
  }
  LevelSimulation direct(scene);
  direct.step();
  const Positions& rest = scene.bodies[0].mesh.vertices;
  const double sag = relative_distance(direct.positions(), rest, rest).second;
  const auto [rms, max] = relative_distance(psq.positions(psq.finest()), direct.positions(), rest);
  EXPECT_GT(sag, 1e-3);        // the load does something
  EXPECT_LT(max, 1e-3 * sag);  // the same equilibrium, to the solver's tolerance
  EXPECT_LT(rms, 1e-3 * sag);
  // Each level kept its state; the clamp is exact on every level.
  for (int l = 0; l < psq.finest(); ++l) {
    const Positions& kept = psq.records()[l].positions;
    ASSERT_EQ(kept.rows(), psq.hierarchy().levels[l].rest.num_vertices());
    const std::vector<int> groups = level_groups(psq.hierarchy(), l);
    for (int v = 0; v < kept.rows(); ++v)
      if (groups[v] == 0) EXPECT_EQ(kept.row(v), psq.hierarchy().levels[l].rest.vertices.row(v));
    EXPECT_GT(psq.records()[l].newton_iterations, 0);
    EXPECT_TRUE(psq.records()[l].equilibrium);
  }
  EXPECT_GT(psq.records()[1].refine_seconds, 0.0);
}

TEST(ProgressiveSimulation, APreviewRestsOnceItsSolvesMoveLessThanTheTolerance) {
  // PSQ Algorithm 1 line 10: a preview's capped solves stop stepping once the change they
  // make is small, ‖d‖₂ < √n_l h ε, whether or not the last one met the Newton tolerance;
  // the finest level must still meet it.
  Scene scene = curved_cantilever(16, 40);  // 697 vertices
  scene.progressive.level_vertices = {60, 200};
  scene.progressive.preview_iterations = 2;
  ProgressiveSimulation psq(scene);
  const double tolerance = psq.current().scene().solver.tolerance;
  const double epsilon = tolerance * psq.current().characteristic_length();
  auto settle_and_check = [&](int max_solves) {
    int capped_at_rest = 0;
    for (int k = 0; k < max_solves; ++k) {
      const Positions before = psq.current().positions();
      const StepRecord r = psq.settle();
      const Positions after = psq.current().positions();
      const double change = (after - before).norm() / std::sqrt(double(after.rows()));
      EXPECT_NEAR(r.change_rms, change, 1e-12 + 1e-9 * change);
      const bool converged = r.newton.stop == NewtonStop::converged;
      const bool at_rest =
          psq.level() < psq.finest()
              ? (converged || r.newton.stop == NewtonStop::max_iterations) && r.change_rms < epsilon
              : converged;
      EXPECT_EQ(r.equilibrium, at_rest && r.script_reached >= 1.0) << "solve " << k;
      if (r.equilibrium) return capped_at_rest + !converged;
    }
    ADD_FAILURE() << "level " << psq.level() << " not at rest after " << max_solves << " solves";
    return capped_at_rest;
  };
  psq.step();
  int capped_at_rest = settle_and_check(300);
  while (psq.level() < psq.finest()) {
    psq.refine();
    capped_at_rest += settle_and_check(300);
  }
  EXPECT_GT(capped_at_rest, 0) << "no preview came to rest on a capped solve";
}

TEST(ProgressiveSimulation, PlateBucklesTheSameWayOnEveryLevel) {
  // Pressed sides buckle the plate up or down; the imperfection picks up. Every level, its
  // preview and the direct finest solve must agree (PSQ §5, Fig. 16).
  const Scene scene = buckling_plate(24, 1e-4, 10);  // 625 vertices
  Scene progressive = scene;
  progressive.progressive.level_vertices = {50, 160};
  ProgressiveSimulation psq(progressive);
  const int centre = 12 * 25 + 12;
  for (int s = 0; s < scene.num_steps(); ++s) psq.step();
  ASSERT_TRUE(psq.settle_to_equilibrium(300));
  const Positions preview = psq.positions(psq.finest());
  EXPECT_GT(preview(centre, 2), 0.05) << "level 0";  // far beyond the 0.1 mm imperfection
  while (psq.level() < psq.finest()) {
    psq.refine();
    ASSERT_TRUE(psq.settle_to_equilibrium(300));
    EXPECT_GT(psq.positions(psq.finest())(centre, 2), 0.05) << "level " << psq.level();
  }
  LevelSimulation direct(scene);
  for (int s = 0; s < scene.num_steps(); ++s) direct.step();
  EXPECT_GT(direct.positions()(centre, 2), 0.05) << "direct finest";
  // Consistency (measured: preview max 0.61% of the diagonal, direct coarse 0.85%).
  LevelSimulation coarse(progressive, SimulationLevel{psq.shared_hierarchy(), 0, {}});
  for (int s = 0; s < scene.num_steps(); ++s) coarse.step();
  const Positions& rest = scene.bodies[0].mesh.vertices;
  const Positions finest = psq.positions(psq.finest());
  const auto [preview_rms, preview_max] = relative_distance(preview, finest, rest);
  const auto [coarse_rms, coarse_max] =
      relative_distance(psq.prolong_to_finest(0, coarse.positions()), finest, rest);
  std::cout << "plate: preview error rms " << preview_rms << " max " << preview_max
            << "; direct coarse rms " << coarse_rms << " max " << coarse_max << "\n";
  EXPECT_LT(preview_max, 0.01);
  EXPECT_LT(preview_max, coarse_max);
}

TEST(ProgressiveSimulation, GalerkinPreviewNeedsFewerIterationsForTheSameEquilibrium) {
  Scene scene = buckling_plate(24, 1e-4, 10);
  scene.progressive.level_vertices = {50, 160};
  std::vector<Positions> previews;
  std::vector<int> iterations;
  for (ProxyHessian hessian : {ProxyHessian::level, ProxyHessian::galerkin}) {
    scene.progressive.hessian = hessian;
    ProgressiveSimulation psq(scene);
    for (int s = 0; s < scene.num_steps(); ++s) psq.step();
    ASSERT_TRUE(psq.settle_to_equilibrium(300));
    previews.push_back(psq.positions(psq.finest()));
    iterations.push_back(psq.records()[0].newton_iterations);
  }
  std::cout << "preview Newton iterations: level Hessian " << iterations[0] << ", Galerkin "
            << iterations[1] << "\n";
  EXPECT_LT(3 * iterations[1], iterations[0]);
  const Positions& rest = scene.bodies[0].mesh.vertices;
  EXPECT_LT(relative_distance(previews[1], previews[0], rest).second, 1e-3);
}

TEST(ProgressiveSimulation, CoarseLevelsEvaluateTheFinestElasticsThroughTheProxy) {
  Scene scene = curved_cantilever(8, 20);
  scene.progressive.level_vertices = {40};
  ProgressiveSimulation psq(scene);
  auto names = [&] {
    std::vector<std::string> out;
    for (const TermStats& t : psq.current().term_totals())
      if (t.gradient_evaluations > 0) out.push_back(t.name);
    return out;
  };
  psq.step();
  EXPECT_EQ(names(), (std::vector<std::string>{"prolonged_elastics", "membrane@finest",
                                               "bending@finest", "gravity@finest"}));
  psq.refine();
  psq.settle();
  EXPECT_EQ(names(), (std::vector<std::string>{"membrane", "bending", "gravity"}));
}

TEST(ProgressiveSimulation, PositionsOfEveryLevel) {
  Scene scene = curved_cantilever(8, 20);  // 189 vertices
  scene.progressive.level_vertices = {30, 80};
  ProgressiveSimulation psq(scene);
  psq.step();
  EXPECT_EQ(psq.positions(0).rows(), 30);
  EXPECT_EQ(psq.positions(1).rows(), 80);  // prolonged
  EXPECT_EQ(psq.positions(2).rows(), 189);
  const Positions level0 = psq.positions(0);
  psq.refine();
  EXPECT_EQ(psq.positions(0), level0);  // kept
  EXPECT_THROW(psq.positions(3), Error);
  EXPECT_THROW(psq.positions(-1), Error);
}

TEST(ProgressiveSimulation, ParametersChangeBetweenPreviewSteps) {
  Scene scene = curved_cantilever(8, 20);
  scene.progressive.level_vertices = {40};
  ProgressiveSimulation psq(scene);
  psq.step();
  psq.settle_to_equilibrium(300);
  const double stiff_tip = psq.positions(1).col(2).minCoeff();
  Scene softer = scene;
  softer.bodies[0].material.youngs_modulus /= 10.0;
  psq.update_scene(softer);
  psq.settle_to_equilibrium(300);
  EXPECT_LT(psq.positions(1).col(2).minCoeff(), stiff_tip - 1e-5);  // sags further
  Scene relevelled = softer;
  relevelled.progressive.level_vertices = {50};
  EXPECT_THROW(psq.update_scene(relevelled), Error);
  Scene other_handles = softer;
  other_handles.handles[0].vertices.pop_back();
  EXPECT_THROW(psq.update_scene(other_handles), Error);
  psq.settle();  // still usable after the refused edits
}

TEST(ProgressiveSimulation, SwitchingToDynamicIsRefusedOnSeveralLevelsAndChangesNothing) {
  Scene scene = curved_cantilever(8, 20);
  scene.time_step = 0.01;
  scene.progressive.level_vertices = {40};
  Scene dynamic = scene;
  dynamic.mode = StepMode::dynamic;
  ProgressiveSimulation psq(scene);
  psq.step();
  const Positions before = psq.positions(0);
  expect_error([&] { psq.update_scene(dynamic); }, Status::unsupported,
               {"update_scene: PSQ is quasistatic", "Progressive Dynamics"});
  EXPECT_EQ(psq.scene().mode, StepMode::quasistatic);
  EXPECT_EQ(psq.current().scene().mode, StepMode::quasistatic);
  EXPECT_EQ(psq.current().steps_taken(), 1);
  EXPECT_EQ(psq.positions(0), before);
  psq.step();  // still a PSQ preview
  EXPECT_EQ(psq.current().velocities().norm(), 0.0);
  // On a single level it is a direct simulation, which steps either mode.
  scene.progressive.level_vertices.clear();
  dynamic.progressive.level_vertices.clear();
  ProgressiveSimulation direct(scene);
  direct.step();
  direct.update_scene(dynamic);
  EXPECT_EQ(direct.current().scene().mode, StepMode::dynamic);
  direct.step();
  EXPECT_GT(direct.current().velocities().norm(), 0.0);
}

TEST(ProgressiveSimulation, RefusesWhatItCannotDo) {
  Scene scene = curved_cantilever(8, 20);
  scene.progressive.level_vertices = {40};
  Scene dynamic = scene;
  dynamic.mode = StepMode::dynamic;
  try {
    ProgressiveSimulation psq(dynamic);
    FAIL() << "dynamic progressive simulation was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::unsupported);
  }
  ProgressiveSimulation psq(scene);
  psq.refine();
  try {
    psq.refine();
    FAIL() << "refined beyond the finest level";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::out_of_range);
  }
  // A hierarchy of another mesh, or without the scene's handles, is refused.
  Scene other = curved_cantilever(8, 21);
  other.progressive.level_vertices = {40};
  EXPECT_THROW(ProgressiveSimulation(other, psq.shared_hierarchy()), Error);
  HierarchyOptions no_groups;
  no_groups.coarse_vertex_counts = {40};
  auto plain =
      std::make_shared<const MeshHierarchy>(build_hierarchy(scene.bodies[0].mesh, no_groups));
  EXPECT_THROW(ProgressiveSimulation(scene, plain), Error);
}
