// Convergence of the bending models under mesh refinement (issue 31): a cantilever strip under
// its own weight (small deflection, ν = 0) against Euler–Bernoulli q L⁴ / (8 E I), on the
// alternating-diagonal grid, the one-diagonal grid and a randomly perturbed grid, for hinge
// and mid-edge bending.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "energy/fitted_midedge_bending.hpp"
#include "energy/gravity.hpp"
#include "energy/hinge_bending.hpp"
#include "energy/lumped_mass.hpp"
#include "energy/midedge_bending.hpp"
#include "energy/neo_hookean_membrane.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_topology.hpp"
#include "problem/problem.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "solve/newton_solver.hpp"
#include "support/rolled_sheets.hpp"
#include "support/sze_strip.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

constexpr double kBeamLength = 0.5, kBeamWidth = 0.1, kBeamThickness = 1e-3, kBeamModulus = 1e11;
constexpr double kBeamDensity = 1000.0, kBeamGravity = 9.81;

enum class GridPattern { alternating, one_diagonal, perturbed };

/// A kBeamLength × kBeamWidth strip of nx × nx/5 quads: make_grid's alternating diagonals, every
/// quad split along the same diagonal, or the alternating grid with its interior vertices beyond
/// the clamp moved in-plane by up to 0.2 of a cell (a fixed seed).
TriangleMesh strip_mesh(int nx, GridPattern pattern) {
  const int ny = nx / 5;
  if (pattern == GridPattern::one_diagonal)
    return one_diagonal_grid(kBeamLength, kBeamWidth, nx, ny);
  if (pattern == GridPattern::perturbed)  // the clamp's columns 0 and 1 stay straight
    return jittered_grid(kBeamLength, kBeamWidth, nx, ny, 0.2, 2);
  return make_grid(kBeamLength, kBeamWidth, nx, ny);
}

/// Tip deflection over q L⁴/(8 E I) of the strip clamped on x ≤ a = L/nx (free length L − a),
/// with the given bending model; mean of the last column.
double tip_over_theory(int nx, GridPattern pattern, BendingModel model) {
  const TriangleMesh mesh = strip_mesh(nx, pattern);
  ShellMaterial m;
  m.youngs_modulus = kBeamModulus;
  m.poisson_ratio = 0.0;
  m.thickness = kBeamThickness;
  m.density = kBeamDensity;
  m.bending_model = model;
  const std::vector<ShellMaterial> materials(mesh.num_faces(), m);
  const std::vector<Hinge> hinges = build_topology(mesh.faces, mesh.num_vertices()).hinges;
  Problem problem(3 * mesh.num_vertices());
  problem.add_term(std::make_unique<NeoHookeanMembrane>(mesh.vertices, mesh.faces, materials));
  if (model == BendingModel::midedge)
    problem.add_term(
        std::make_unique<MidedgeBending>(mesh.vertices, mesh.faces, hinges, materials));
  else if (model == BendingModel::midedge_fitted)
    problem.add_term(
        std::make_unique<FittedMidedgeBending>(mesh.vertices, mesh.faces, hinges, materials));
  else
    problem.add_term(std::make_unique<HingeBending>(mesh.vertices, mesh.faces, hinges, materials));
  problem.add_term(std::make_unique<Gravity>(
      lumped_vertex_masses(mesh.vertices, mesh.faces, materials), Vec3(0, 0, -kBeamGravity)));
  const double a = kBeamLength / nx;
  std::vector<bool> fixed(3 * mesh.num_vertices(), false);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.vertices(v, 0) <= a * (1.0 + 1e-9))
      for (int k = 0; k < 3; ++k) fixed[3 * v + k] = true;
  problem.set_fixed_dofs(fixed);
  problem.finalize();
  Vector x = as_dofs(mesh.vertices);
  NewtonSettings settings;
  settings.tolerance = 1e-9;
  settings.max_iterations = 300;
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, settings, 1.0, 1.0);
  EXPECT_EQ(report.stop, NewtonStop::converged) << stop_name(report.stop);
  const double free_length = kBeamLength - a;
  const double ei = kBeamModulus * std::pow(kBeamThickness, 3) / 12.0;  // per unit width
  const double q = kBeamDensity * kBeamThickness * kBeamGravity;        // N/m²
  const double expected = q * std::pow(free_length, 4) / (8.0 * ei);    // Euler–Bernoulli
  EXPECT_LT(expected / free_length, 0.05) << "not a small deflection";
  double tip = 0.0;
  int count = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.vertices(v, 0) >= kBeamLength * (1.0 - 1e-9)) {
      tip += -x[3 * v + 2];
      ++count;
    }
  return tip / count / expected;
}

const char* pattern_name(GridPattern p) {
  return p == GridPattern::alternating
             ? "alternating"
             : (p == GridPattern::one_diagonal ? "one diagonal" : "perturbed");
}

}  // namespace

TEST(BendingConvergence, MidedgeCantileverConvergesToBeamTheoryOnRegularGrids) {
  // Measured (tip / theory with free length L − a, nx = 20, 40, 80 cells along, nx/5 across):
  //   alternating   hinge 1.323 1.275 1.252   midedge 1.108 1.052 1.025
  //   one diagonal  hinge 1.332 1.272 1.243   midedge 1.108 1.052 1.025
  //   perturbed     hinge 1.233 1.199 1.168   midedge 1.056 1.000 0.965
  // Mid-edge bending converges at first order on both regular grids (the error halves per
  // refinement, 2.5 % at 80). That error is the clamp's, not the bending energy's: the clamp's
  // last edge, at x = a, carries the mean of a clamped and a free face normal, so mid-edge
  // bending holds the rotation half a cell further in. Against free length L − a/2 it is within
  // 0.2 % at every size (0.9985, 0.9994, 0.9997) and hinge bending 19, 21, 22 % soft (issue
  // 31's figures). On the perturbed grid (interior vertices beyond the clamp moved by up to 0.2
  // cell) the mid-edge average does not converge: 0.952, 0.950, 0.941 against L − a/2, i.e.
  // 5–6 % too stiff (the averaged edge normals are not consistent on irregular meshes, which is
  // what Grinspun et al. 2006's per-edge normal DOFs fix); asserted only to beat hinge there.
  // Fitted normals (FittedMidedgeBending) give the bisector's values on both regular grids and
  // converge on the perturbed one: 1.1050, 1.0506, 1.0246 (0.9959, 0.9984, 0.9991 against
  // L − a/2).
  std::printf("[ bending  ] cantilever tip / (q L^4 / 8EI), nu = 0\n");
  std::printf("[ bending  ] %-13s %4s %9s %9s %16s %9s %6s\n", "mesh", "nx", "hinge", "midedge",
              "midedge, L - a/2", "fitted", "L-a/2");
  for (GridPattern pattern :
       {GridPattern::alternating, GridPattern::one_diagonal, GridPattern::perturbed}) {
    double previous_error = 1.0, previous_fitted_error = 1.0;
    for (int nx : {20, 40, 80}) {
      const double hinge = tip_over_theory(nx, pattern, BendingModel::hinge);
      const double midedge = tip_over_theory(nx, pattern, BendingModel::midedge);
      const double half_cell =  // (L − a/2)⁴ / (L − a)⁴
          std::pow((kBeamLength - 0.5 * kBeamLength / nx) / (kBeamLength - kBeamLength / nx), 4);
      const double fitted = tip_over_theory(nx, pattern, BendingModel::midedge_fitted);
      std::printf("[ bending  ] %-13s %4d %9.4f %9.4f %16.4f %9.4f %6.4f\n", pattern_name(pattern),
                  nx, hinge, midedge, midedge / half_cell, fitted, fitted / half_cell);
      const double error = std::abs(midedge - 1.0);
      EXPECT_LT(2.0 * std::abs(midedge / half_cell - 1.0), std::abs(hinge / half_cell - 1.0))
          << pattern_name(pattern) << ", nx = " << nx;
      EXPECT_GT(hinge - 1.0, 0.15) << "hinge bending was measured 17-33 % soft";
      // Fitted normals converge on every mesh, the perturbed one included (issue 31's 3 %).
      EXPECT_NEAR(fitted / half_cell, 1.0, 0.005) << pattern_name(pattern) << ", nx = " << nx;
      EXPECT_LT(std::abs(fitted - 1.0), previous_fitted_error) << pattern_name(pattern);
      previous_fitted_error = std::abs(fitted - 1.0);
      if (nx == 80) {
        EXPECT_LT(previous_fitted_error, 0.03) << pattern_name(pattern);
      }
      if (pattern == GridPattern::perturbed) continue;
      EXPECT_NEAR(midedge / half_cell, 1.0, 0.005) << pattern_name(pattern) << ", nx = " << nx;
      EXPECT_LT(error, previous_error) << pattern_name(pattern) << ", nx = " << nx;
      if (nx == 80) {
        EXPECT_LT(error, 0.03) << pattern_name(pattern);
      }
      previous_error = error;
    }
  }
}

namespace {

/// A small grid body named `name` with the given JSON material fields.
std::string grid_body(const std::string& name, const std::string& material) {
  return R"({"name": ")" + name +
         R"(", "mesh": {"generator": "grid", "width": 1, "height": 1, "nx": 2, "ny": 2},
             "material": {)" +
         material + "}}";
}

/// A quasistatic scene of one body (second_material empty) or two with these materials.
std::string bending_scene(const std::string& material, const std::string& second_material) {
  std::string bodies = grid_body("a", material);
  if (!second_material.empty()) bodies += ", " + grid_body("b", second_material);
  return R"({"simulation": {"mode": "quasistatic"}, "effects": ["membrane", "bending"],
             "bodies": [)" +
         bodies + "]}";
}

}  // namespace

TEST(BendingConvergence, SceneMaterialSelectsTheBendingModel) {
  const Scene hinge = parse_scene(bending_scene("", ""), ".");
  EXPECT_EQ(hinge.bodies[0].material.bending_model, BendingModel::hinge);  // the default
  LevelSimulation with_hinge(hinge);
  EXPECT_NE(dynamic_cast<const HingeBending*>(with_hinge.problem().find_term("bending")), nullptr);
  const Scene midedge = parse_scene(bending_scene(R"("bending_model": "midedge")", ""), ".");
  LevelSimulation with_midedge(midedge);
  EXPECT_NE(dynamic_cast<const MidedgeBending*>(with_midedge.problem().find_term("bending")),
            nullptr);
  const Scene fitted = parse_scene(bending_scene(R"("bending_model": "midedge_fitted")", ""), ".");
  LevelSimulation with_fitted(fitted);
  EXPECT_NE(dynamic_cast<const FittedMidedgeBending*>(with_fitted.problem().find_term("bending")),
            nullptr);
  EXPECT_THROW(parse_scene(bending_scene(R"("bending_model": "kirchhoff")", ""), "."), Error);
  // One model per scene: bodies that disagree are refused.
  EXPECT_THROW(
      LevelSimulation(parse_scene(
          bending_scene(R"("bending_model": "midedge")", R"("bending_model": "hinge")"), ".")),
      Error);
}

TEST(BendingConvergence, ProgressiveLevelsUseTheSelectedModelUpToTheFinest) {
  // PSQ with mid-edge bending, bisected and fitted normals: the preview's proxy evaluates the
  // finest shell terms make_shell_elastics builds (the selected model), and refining to the
  // finest level settles where a direct solve with that model does (the preview and the direct
  // solve share no code path but the terms).
  for (const std::string model : {"midedge", "midedge_fitted"}) {
    SCOPED_TRACE(model);
    Scene scene = parse_scene(R"({
      "simulation": {"mode": "quasistatic", "time_step": 1, "duration": 1},
      "effects": ["membrane", "bending", "gravity"], "gravity": [0, 0, -9.81],
      "solver": {"newton_tolerance": 1e-9, "max_newton_iterations": 300},
      "bodies": [{"name": "strip", "mesh": {"generator": "grid", "width": 0.5, "height": 0.1,
                  "nx": 25, "ny": 4}, "material": {"youngs_modulus": 1e9, "poisson_ratio": 0,
                  "thickness": 1e-3, "density": 1000, "bending_model": ")" +
                                  model + R"("}}],
      "handles": [{"body": "strip", "box": {"min": [-0.01, -0.01, -0.01],
                                            "max": [0.021, 0.11, 0.01]}}],
      "progressive": {"levels": [40], "preview_iterations": 50}})",
                              ".");
    ProgressiveSimulation psq(scene);
    psq.step();
    bool through_proxy = false;
    for (const TermStats& s : psq.current().term_totals())
      through_proxy = through_proxy || (s.name == "bending@finest" && s.gradient_evaluations > 0);
    EXPECT_TRUE(through_proxy);
    psq.refine();
    EXPECT_TRUE(psq.settle_to_equilibrium(20));
    LevelSimulation direct(scene);
    const EnergyTerm* bending = direct.problem().find_term("bending");
    if (model == "midedge")
      ASSERT_NE(dynamic_cast<const MidedgeBending*>(bending), nullptr);
    else
      ASSERT_NE(dynamic_cast<const FittedMidedgeBending*>(bending), nullptr);
    direct.step();
    const Positions finest = psq.positions(psq.finest());
    const Positions reference(direct.positions());
    EXPECT_LT(reference.col(2).minCoeff(), -1e-3) << "the strip sags";
    EXPECT_LT((finest - reference).cwiseAbs().maxCoeff(), 1e-6);
  }
}

namespace {

/// Sze, Liu & Lo (2004) §3.1: the strip (support/sze_strip.hpp, E I = 100) under an end shear
/// P up to P_max = 4, i.e. P L² / E I = 2 and 4.
constexpr double kSzeMaxLoad = 4.0;
constexpr const char* kModelNames[] = {"hinge", "midedge", "fitted"};  // BendingModel's order

/// Tip displacements (−u, w) of Sze's cantilever at P = P_max/2 and P_max (two quasistatic
/// load steps of a ramped dead load, spread over the tip edge by area), nx cells along and
/// nx/10 across. Mid-edge bending holds the rotation halfway between the clamp's two columns
/// (see MidedgeCantileverConvergesToBeamTheoryOnRegularGrids), so the strip starts half a
/// cell behind x = 0 and is clamped on its first two columns, at x = ∓a/2: the free length is
/// L for mid-edge bending.
std::array<Vec3, 2> sze_tip_displacements(int nx, BendingModel model) {
  const double a = kSzeLength / (nx - 0.5);
  Scene scene = sze_strip_scene("sze_end_shear", -0.5 * a, kSzeLength, nx, model, 0.5);
  const TriangleMesh& mesh = scene.bodies[0].mesh;
  Handle clamp;
  clamp.vertices = sze_vertices_below(scene, a);
  Load shear;
  shear.force = Vec3(0, 0, -kSzeMaxLoad);
  shear.distribution = LoadDistribution::area;
  shear.ramp = 1.0;  // P = P_max t
  shear.vertices = sze_vertices_above(scene, kSzeLength - 1e-9);
  scene.handles.push_back(clamp);
  scene.loads.push_back(shear);
  LevelSimulation sim(scene);
  std::array<Vec3, 2> tips;
  for (Vec3& tip : tips) {
    const StepRecord r = sim.step();
    if (model != BendingModel::hinge)  // hinge's run at nx = 80 took over 500 iterations
      EXPECT_EQ(r.newton.stop, NewtonStop::converged) << stop_name(r.newton.stop);
    tip.setZero();
    for (int v : shear.vertices)
      tip += sim.positions().row(v).transpose() - mesh.vertices.row(v).transpose();
    tip /= static_cast<double>(shear.vertices.size());
    tip = Vec3(-tip.x(), -tip.z(), tip.y());  // (−u, w, lateral)
  }
  return tips;
}

}  // namespace

TEST(BendingConvergence, MidedgeCantileverUnderEndShearMatchesSzeBenchmark) {
  // Published (Sze, Liu & Lo 2004, Table 1, S4R 16 × 1 mesh): −u, w = 1.604, 4.933 at
  // P/P_max = 0.5 and 3.286, 6.698 at 1, asserted within 3 % (issue 31). Convergence is
  // measured against the inextensible elastica θ'' = −(P L²/E I) cos θ, θ(0) = 0, θ'(L) = 0
  // (Mattiasson 1981's problem), solved by shooting with RK4 in tests/data/elastica.py:
  // 1.6064, 4.9346 and 3.2894, 6.6996.
  // Measured: mid-edge within 0.22 % of Sze at every size, its largest error against the
  // elastica 0.11 %, 0.03 %, 0.01 % at nx = 20, 40, 80; hinge 24-28 % long in −u at P_max/2;
  // fitted mid-edge normals as the bisected ones (printed).
  const double published[2][2] = {{1.604, 4.933}, {3.286, 6.698}};
  const double elastica[2][2] = {{1.6064, 4.9346}, {3.2894, 6.6996}};
  std::printf("[ sze 3.1  ] %-8s %4s %6s %8s %8s %8s %8s %9s\n", "model", "nx", "P/Pmax", "-u", "w",
              "-u err", "w err", "elastica");
  double previous_error[2] = {1.0, 1.0};  // mid-edge, fitted
  for (int nx : {20, 40, 80}) {
    for (BendingModel model :
         {BendingModel::hinge, BendingModel::midedge, BendingModel::midedge_fitted}) {
      const std::array<Vec3, 2> tips = sze_tip_displacements(nx, model);
      double worst = 0.0, worst_elastica = 0.0;
      for (int k = 0; k < 2; ++k) {
        const double eu = tips[k].x() / published[k][0] - 1.0;
        const double ew = tips[k].y() / published[k][1] - 1.0;
        const double ee = std::max(std::abs(tips[k].x() / elastica[k][0] - 1.0),
                                   std::abs(tips[k].y() / elastica[k][1] - 1.0));
        std::printf("[ sze 3.1  ] %-8s %4d %6.1f %8.4f %8.4f %+7.2f%% %+7.2f%% %8.3f%%\n",
                    kModelNames[static_cast<int>(model)], nx, 0.5 * (k + 1), tips[k].x(),
                    tips[k].y(), 100 * eu, 100 * ew, 100 * ee);
        EXPECT_LT(std::abs(tips[k].z()), 1e-6) << "the strip moved sideways";
        worst = std::max({worst, std::abs(eu), std::abs(ew)});
        worst_elastica = std::max(worst_elastica, ee);
      }
      if (model == BendingModel::hinge) {
        EXPECT_GT(worst, 0.1) << "hinge bending was measured 24-28 % off";
        continue;  // reported for comparison
      }
      EXPECT_LT(worst, 0.03) << "nx = " << nx;
      double& previous = previous_error[model == BendingModel::midedge_fitted];
      EXPECT_LT(worst_elastica, previous) << "nx = " << nx;
      previous = worst_elastica;
    }
  }
}
