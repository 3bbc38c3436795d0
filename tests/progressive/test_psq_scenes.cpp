// The bundled PSQ scenes (scenes/psq_*.json) at CI sizes, through the accuracy run: on every
// level, progressive and direct, no face pairs of the shell and obstacles cross (CGAL's exact
// check), the progressive finest level ends at equilibrium, and the states stay finite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <utility>
#include <vector>

#include "progressive/accuracy.hpp"
#include "progressive/progressive_simulation.hpp"
#include "progressive/state_distance.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;

namespace {

using Edits = std::vector<std::pair<std::string, std::string>>;

/// A bundled scene with parts of its JSON text replaced (smaller meshes and fewer load steps
/// than the bundled sizes, for CI). Every edit must apply.
Scene bundled(const std::string& file, const Edits& edits) {
  const std::string dir = std::string(PROGSIM_SOURCE_DIR) + "/scenes";
  std::ifstream in(dir + "/" + file);
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  for (const auto& [from, to] : edits) {
    const auto at = json.find(from);
    EXPECT_NE(at, std::string::npos) << file << ": no '" << from << "'";
    if (at != std::string::npos) json.replace(at, from.size(), to);
  }
  return parse_scene(json, dir);
}

/// Every row crossing-free; the finest level at equilibrium, progressive and direct.
void expect_safe_and_converged(const AccuracyReport& report) {
  for (const AccuracyRow& row : report.rows) {
    SCOPED_TRACE(
        (row.method == AccuracyRow::Method::progressive ? "progressive level " : "direct level ") +
        std::to_string(row.level));
    EXPECT_EQ(row.intersecting_pairs, 0);
    EXPECT_TRUE(std::isfinite(row.error_rms));
  }
  const AccuracyRow& finest = report.rows[report.rows.size() / 2 - 1];
  ASSERT_EQ(finest.method, AccuracyRow::Method::progressive);
  EXPECT_TRUE(finest.converged);
  // The baseline is worth comparing with: the direct finest solve converged too.
  ASSERT_EQ(report.rows.back().method, AccuracyRow::Method::direct);
  EXPECT_TRUE(report.rows.back().converged);
}

/// Expects each coarse level's preview nearer the converged result than the direct solve of
/// that level, in RMS and in max (rows: progressive levels 0..L, then direct levels 0..L).
void expect_previews_closer_than_direct_coarse_solves(const AccuracyReport& report,
                                                      const char* scene) {
  const int levels = static_cast<int>(report.rows.size()) / 2;
  for (int level = 0; level + 1 < levels; ++level) {
    const AccuracyRow& preview = report.rows[level];
    const AccuracyRow& direct = report.rows[levels + level];
    ASSERT_EQ(preview.method, AccuracyRow::Method::progressive);
    ASSERT_EQ(preview.level, level);
    ASSERT_EQ(direct.method, AccuracyRow::Method::direct);
    ASSERT_EQ(direct.level, level);
    std::printf("[ %s ] level %d: preview RMS %.5f max %.5f; direct RMS %.5f max %.5f\n", scene,
                level, preview.error_rms, preview.error_max, direct.error_rms, direct.error_max);
    EXPECT_LT(preview.error_rms, direct.error_rms) << "level " << level;
    EXPECT_LT(preview.error_max, direct.error_max) << "level " << level;
  }
}

/// The names of the terms `sim` evaluates, the proxy's finest ones as "<term>@finest".
std::vector<std::string> term_names(const LevelSimulation& sim) {
  std::vector<std::string> names;
  for (const TermStats& t : sim.term_totals()) names.push_back(t.name);
  return names;
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

TEST(PsqScenes, ClothOnSphereIsIntersectionFreeOnEveryLevel) {
  // 961 vertices (levels 60 / 240 / 961): at 441 the coarsest level has 28 vertices, too few
  // to say which of two coarse solutions is nearer (measured 0.100 vs 0.103 of the diagonal).
  const Scene scene =
      bundled("psq_cloth_on_sphere.json", {{R"("nx": 40, "ny": 40)", R"("nx": 30, "ny": 30)"}});
  ASSERT_EQ(scene.bodies[0].mesh.num_vertices(), 961);
  ASSERT_EQ(scene.progressive.preview_membrane, MembraneModel::tension_field);
  const AccuracyReport report = run_accuracy(scene);
  ASSERT_EQ(report.rows.size(), 6u);
  expect_safe_and_converged(report);
  // The coarse preview lies within a tenth of the diagonal of the converged result, nearer it
  // than the direct coarse solve (measured: level 0 0.060 vs 0.079 RMS, 0.158 vs 0.182 max;
  // level 1 0.020 vs 0.039, 0.064 vs 0.127; with the neo-Hookean preview membrane level 0 is
  // 0.083 vs 0.073).
  EXPECT_LT(report.rows[0].error_rms, 0.1);
  expect_previews_closer_than_direct_coarse_solves(report, "drape");
  // The sphere is a progressive collision object: the report says the previews met coarser
  // copies of it than the direct solves, which meet all of its vertices.
  const int sphere = scene.obstacles[0].mesh.num_vertices();
  EXPECT_EQ(report.obstacle_vertices, sphere);
  ASSERT_EQ(report.progressive_obstacle_vertices.size(), 3u);
  EXPECT_LT(report.progressive_obstacle_vertices[0], report.progressive_obstacle_vertices[1]);
  EXPECT_LT(report.progressive_obstacle_vertices[1], sphere);
  EXPECT_EQ(report.progressive_obstacle_vertices[2], sphere);
  EXPECT_NE(accuracy_markdown(report).find("every direct solve met all " + std::to_string(sphere) +
                                           ".\n"),
            std::string::npos);
}

TEST(PsqScenes, TwistIsIntersectionFreeOnEveryLevel) {
  const Scene scene = bundled("psq_twist.json", {{R"("nx": 32, "ny": 32)", R"("nx": 16, "ny": 16)"},
                                                 {R"("duration": 20.0)", R"("duration": 10.0)"}});
  const AccuracyReport report = run_accuracy(scene);
  ASSERT_EQ(report.rows.size(), 6u);
  expect_safe_and_converged(report);
}

/// What the Newton solves of a direct run did over its steps.
struct DirectRun {
  int iterations = 0, cg_iterations = 0, converged_steps = 0;
};

/// The scene solved directly over its first `steps` steps.
static DirectRun solve_directly(const Scene& scene, int steps) {
  LevelSimulation sim(scene);
  DirectRun run;
  for (int s = 0; s < steps; ++s) {
    const StepRecord r = sim.step();
    run.iterations += r.newton.iterations;
    run.cg_iterations += r.newton.cg_iterations;
    run.converged_steps += r.newton.stop == NewtonStop::converged;
  }
  return run;
}

TEST(PsqScenes, TwistConvergesInFewerIterationsWhenProjectedStepsFollowTheExactCurvature) {
  // Wringing compresses the cloth, so its Hessian is indefinite and Newton projects it; the
  // projection also discards the curvature of soft folding modes, and projected steps creep
  // along them. CG against the exact Hessian (truncated_newton.hpp) restores those steps.
  Scene scene = bundled("psq_twist.json", {{R"("nx": 32, "ny": 32)", R"("nx": 16, "ny": 16)"}});
  scene.progressive = ProgressiveSettings{};
  const int steps = 6;
  ASSERT_EQ(scene.solver.max_cg_iterations, 0);  // opt-in
  const DirectRun projected = solve_directly(scene, steps);
  scene.solver.max_cg_iterations = 50;
  const DirectRun refined = solve_directly(scene, steps);
  std::cout << "[ twist ] Newton iterations over " << steps << " steps: projected "
            << projected.iterations << ", CG-refined " << refined.iterations << " ("
            << refined.cg_iterations << " CG iterations)" << std::endl;
  EXPECT_EQ(projected.cg_iterations, 0);
  EXPECT_GT(refined.cg_iterations, 0);
  EXPECT_EQ(refined.converged_steps, steps);
  EXPECT_LT(refined.iterations, 0.85 * projected.iterations);
}

TEST(PsqScenes, BalloonInflatedAgainstAPlateIsIntersectionFreeOnEveryLevel) {
  const AccuracyReport report = run_accuracy(bundled("psq_balloon.json", {}));
  ASSERT_EQ(report.rows.size(), 6u);
  expect_safe_and_converged(report);
}

TEST(PsqScenes, StiffThinCanCrushStaysFiniteAndIntersectionFree) {
  const Scene scene =
      bundled("psq_can_crush.json",
              {{R"("n_around": 72, "n_along": 24)", R"("n_around": 24, "n_along": 8)"}});
  const AccuracyReport report = run_accuracy(scene, 100);
  ASSERT_EQ(report.rows.size(), 6u);
  expect_safe_and_converged(report);
  // The whole 10 mm crush happened on every level: at equilibrium means the plate reached its
  // scripted place (a stiff coarse can once held it back from the 4th step on).
  for (const AccuracyRow& row : report.rows) EXPECT_TRUE(row.converged) << "level " << row.level;
}

TEST(PsqScenes, StiffThinCanPreviewDoesNotLockLikeTheDirectCoarseSolve) {
  // PSQ Fig. 4: the direct coarse can locks (its coarse triangles cannot bend without
  // stretching), the preview with the finest elastics buckles like the converged result.
  // Bundled size (1800 vertices, levels of 113 and 450): the CI size's coarsest level has 14.
  const Scene scene = bundled("psq_can_crush.json", {});
  ProgressiveSimulation psq(scene);
  for (int s = 0; s < scene.num_steps(); ++s) psq.step();
  ASSERT_TRUE(psq.settle_to_equilibrium(500));
  while (psq.level() < psq.finest()) {
    psq.refine();
    ASSERT_TRUE(psq.settle_to_equilibrium(500)) << "level " << psq.level();
  }
  LevelSimulation coarse(scene, SimulationLevel{psq.shared_hierarchy(), 0, {}});
  StepRecord last;
  for (int s = 0; s < scene.num_steps(); ++s) last = coarse.step();
  for (int k = 0; k < 500 && !last.equilibrium; ++k) last = coarse.settle();
  ASSERT_TRUE(last.equilibrium);  // fully crushed too
  const Positions finest = psq.positions(psq.finest());
  const double diagonal = bounding_box_diagonal(psq.hierarchy().levels.back().rest.vertices);
  const StateDistance preview = *psq.error_against_finest(0);
  const StateDistance direct =
      state_distance(psq.prolong_to_finest(0, Positions(coarse.positions())), finest, diagonal);
  std::printf("[ can ] preview error RMS %.4f max %.4f; direct coarse RMS %.4f max %.4f\n",
              preview.rms, preview.max, direct.rms, direct.max);
  EXPECT_LT(preview.rms, 0.08);  // measured 0.049
  EXPECT_LT(preview.rms, direct.rms);
  EXPECT_LT(preview.max, direct.max);
}

TEST(PsqScenes, PlateBucklingPreviewsAreCloserThanTheDirectCoarseSolves) {
  // The bundled plate (625 vertices, levels of 39 and 156): on each coarse level the preview,
  // prolonged to the finest mesh, is nearer the converged result than the direct solve of the
  // same level, in RMS and in the largest vertex distance.
  const AccuracyReport report = run_accuracy(bundled("psq_plate_buckling.json", {}));
  ASSERT_EQ(report.rows.size(), 6u);
  expect_safe_and_converged(report);
  EXPECT_LT(report.rows[0].error_rms, 0.01);  // measured 0.0054 of the diagonal
  expect_previews_closer_than_direct_coarse_solves(report, "plate");
}

TEST(PsqScenes, ClothOnSpherePreviewsUseTheTensionFieldMembraneTheFinestLevelTheFullOne) {
  Scene scene =
      bundled("psq_cloth_on_sphere.json", {{R"("nx": 40, "ny": 40)", R"("nx": 20, "ny": 20)"}});
  ASSERT_EQ(scene.progressive.hessian, ProxyHessian::galerkin);
  // Also with the level's own (relaxed) shell Hessian as the preview's Newton matrix.
  for (ProxyHessian hessian : {ProxyHessian::galerkin, ProxyHessian::level}) {
    SCOPED_TRACE(hessian == ProxyHessian::level ? "level Hessian" : "Galerkin Hessian");
    scene.progressive.hessian = hessian;
    ProgressiveSimulation psq(scene);
    for (int s = 0; s < scene.num_steps(); ++s) psq.step();
    EXPECT_TRUE(psq.settle_to_equilibrium(100));
    for (int level = 0; level < psq.finest(); ++level) {
      SCOPED_TRACE("level " + std::to_string(level));
      const std::vector<std::string> names = term_names(psq.current());
      EXPECT_TRUE(has(names, "tension_field_membrane@finest"));
      EXPECT_FALSE(has(names, "membrane@finest"));
      psq.refine();
    }
    EXPECT_TRUE(has(term_names(psq.current()), "membrane"));
    EXPECT_FALSE(has(term_names(psq.current()), "tension_field_membrane"));
  }
  const LevelSimulation coarse(
      scene,
      SimulationLevel{std::make_shared<const MeshHierarchy>(build_scene_hierarchy(scene)), 0, {}});
  EXPECT_TRUE(has(term_names(coarse), "membrane"));
  EXPECT_FALSE(has(term_names(coarse), "tension_field_membrane"));
}

TEST(PsqScenes, ClothOnSphereKeepsItsStrainLimitOnEveryLevel) {
  // The paper's cloth has a strain limit of 1.06 (PSQ supplement Table 1). Safe refinement
  // leaves new vertices that stretch faces far beyond it; the strain-limit correction (PSQ
  // §4.4.5) brings every face of the refined start back under it (stretches by Eigen's SVD).
  const Scene scene =
      bundled("psq_cloth_on_sphere.json", {{R"("nx": 40, "ny": 40)", R"("nx": 20, "ny": 20)"}});
  ASSERT_EQ(scene.bodies[0].material.strain_limit, 1.06);
  ASSERT_TRUE(scene.effects.has(Effect::strain_limit));
  ASSERT_TRUE(scene.obstacles[0].progressive);
  ProgressiveSimulation psq(scene);
  for (int s = 0; s < scene.num_steps(); ++s) psq.step();
  const int sphere_vertices = scene.obstacles[0].mesh.num_vertices();
  for (int level = 0;; ++level) {
    SCOPED_TRACE("level " + std::to_string(level));
    StepRecord last = psq.settle();
    std::printf("[ psq ] level %d: %d faces with a raised strain limit after its first solve\n",
                level, last.raised_limits);
    psq.settle_to_equilibrium(300);
    last = psq.settle();
    for (int k = 0; k < 100 && last.raised_limits > 0; ++k) last = psq.settle();
    EXPECT_EQ(last.raised_limits, 0);
    ASSERT_TRUE(last.max_stretch.has_value());
    EXPECT_LT(*last.max_stretch, 1.06);
    EXPECT_EQ(psq.current().intersecting_face_pairs(), 0u);  // CGAL
    // The progressive sphere (PSQ §4.6): coarse on coarse levels, refined with the cloth
    // (its new vertices placed safely, then carried to their places by the script rounds).
    const LevelRecord& record = psq.records()[level];
    EXPECT_TRUE(record.equilibrium);
    if (level < psq.finest()) EXPECT_LT(record.obstacle_vertices, sphere_vertices);
    if (level > 0) EXPECT_GT(record.obstacle_refinement.splits, 0);
    if (level == psq.finest()) {
      EXPECT_EQ(psq.current().obstacle_positions(), scene.obstacles[0].mesh.vertices);
      break;
    }
    psq.refine();
    const StrainCorrectionStats& correction = psq.records()[level + 1].strain_correction;
    std::printf(
        "[ psq ] refined start of level %d: %d faces beyond the limit (stretch %.3f), "
        "%d after the correction (stretch %.4f, %d Newton iterations)\n",
        level + 1, correction.strained_faces, correction.stretch_before,
        correction.over_limit_faces, correction.stretch_after, correction.newton_iterations);
    EXPECT_GT(correction.strained_faces, 0);  // the correction had work to do
    EXPECT_EQ(correction.over_limit_faces, 0);
    const TriangleMesh& rest = psq.hierarchy().levels[level + 1].rest;
    EXPECT_LT(pt::max_membrane_stretch(rest.vertices, rest.faces, psq.current().dofs()), 1.06);
    EXPECT_EQ(psq.current().intersecting_face_pairs(), 0u);  // CGAL, before any solve
  }
}
