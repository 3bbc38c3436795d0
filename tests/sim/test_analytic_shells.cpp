// Shell elastics against closed-form results: pure bending of a strip (R = EI/M), a
// cantilever plate's tip deflection (q L⁴ / 8D), a hanging cloth at equilibrium, and a
// Neo-Hookean balloon's pressure–stretch curve.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <cmath>
#include <iostream>

#include "energy/gravity.hpp"
#include "energy/hinge_bending.hpp"
#include "energy/neo_hookean_membrane.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_topology.hpp"
#include "problem/problem.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "solve/newton_solver.hpp"
#include "support/end_moment_term.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;

namespace {

/// Radius of the least-squares circle through 2D points (Kåsa fit).
double fitted_circle_radius(const std::vector<Vec2>& points) {
  Eigen::MatrixXd a(points.size(), 3);
  Eigen::VectorXd b(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    a.row(i) << points[i].x(), points[i].y(), 1.0;
    b[i] = points[i].squaredNorm();
  }
  const Eigen::Vector3d c = a.colPivHouseholderQr().solve(b);  // x² + y² = c0 x + c1 y + c2
  return std::sqrt(c[2] + 0.25 * (c[0] * c[0] + c[1] * c[1]));
}

/// A strip or plate of rows of near-equilateral triangles (edge a = length / nx; odd rows
/// shifted by a/2 and closed by half-width triangles at both ends), clamped where x ≤ a.
/// Hinge bending is isotropic on such meshes; on right-triangle grids its fold lines along
/// the diagonals make it softer for free equilibria than the plate it models.
struct ClampedSheet {
  TriangleMesh mesh;
  std::vector<std::vector<int>> rows;  ///< vertex indices of each row, by increasing x
  double spacing, width;
  std::unique_ptr<Problem> problem;

  ClampedSheet(double length, int nx, int num_rows, const ShellMaterial& material)
      : spacing(length / nx), width(num_rows * spacing * std::sqrt(3.0) / 2.0) {
    std::vector<Vec3> points;
    for (int j = 0; j <= num_rows; ++j) {
      rows.emplace_back();
      std::vector<double> xs;
      for (int i = 0; i <= nx; ++i) xs.push_back(i * spacing);
      if (j % 2 == 1) {
        for (int i = 0; i < nx; ++i) xs[i + 1] = (i + 0.5) * spacing;
        xs.push_back(length);
      }
      for (double xv : xs) {
        rows.back().push_back(static_cast<int>(points.size()));
        points.emplace_back(xv, j * width / num_rows, 0.0);
      }
    }
    mesh.vertices.resize(points.size(), 3);
    for (std::size_t v = 0; v < points.size(); ++v) mesh.vertices.row(v) = points[v];
    std::vector<std::array<int, 3>> faces;
    for (int j = 0; j < num_rows; ++j) zip_rows(rows[j], rows[j + 1], faces);
    mesh.faces.resize(faces.size(), 3);
    for (std::size_t f = 0; f < faces.size(); ++f)
      mesh.faces.row(f) << faces[f][0], faces[f][1], faces[f][2];
    const std::vector<ShellMaterial> materials(mesh.num_faces(), material);
    problem = std::make_unique<Problem>(3 * mesh.num_vertices());
    problem->add_term(std::make_unique<NeoHookeanMembrane>(mesh.vertices, mesh.faces, materials));
    problem->add_term(std::make_unique<HingeBending>(
        mesh.vertices, mesh.faces, build_topology(mesh.faces, mesh.num_vertices()).hinges,
        materials));
  }
  /// Triangulates the band between two rows (lower, upper), counter-clockwise seen from +z.
  void zip_rows(const std::vector<int>& lower, const std::vector<int>& upper,
                std::vector<std::array<int, 3>>& faces) const {
    std::size_t i = 0, j = 0;
    const auto x = [&](int v) { return mesh.vertices(v, 0); };
    while (i + 1 < lower.size() || j + 1 < upper.size()) {
      if (j + 1 == upper.size() || (i + 1 < lower.size() && x(lower[i + 1]) < x(upper[j + 1]))) {
        faces.push_back({lower[i], lower[i + 1], upper[j]});
        ++i;
      } else {
        faces.push_back({lower[i], upper[j + 1], upper[j]});
        ++j;
      }
    }
  }
  void clamp_and_finalize() {
    std::vector<bool> fixed(3 * mesh.num_vertices(), false);
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (mesh.vertices(v, 0) <= spacing * (1.0 + 1e-9))
        for (int k = 0; k < 3; ++k) fixed[3 * v + k] = true;
    problem->set_fixed_dofs(fixed);
    problem->finalize();
  }
  Vector solve(double tolerance, HessianProjection projection = HessianProjection::adaptive,
               NewtonReport* out = nullptr, bool extrapolate = true) {
    Vector x = as_dofs(mesh.vertices);
    NewtonSettings settings;
    settings.tolerance = tolerance;
    settings.extrapolate = extrapolate;
    settings.max_iterations = 1000;
    settings.projection = projection;
    NewtonSolver solver;
    const NewtonReport report = solver.minimize(*problem, x, settings, 1.0, 1.0);
    if (out) *out = report;
    EXPECT_EQ(report.stop, NewtonStop::converged)
        << stop_name(report.stop) << " after " << report.iterations << " iterations ("
        << report.exact_steps << " exact), ‖∇E‖ = " << report.gradient_norm
        << ", ‖p‖∞ = " << report.step_norm;
    return x;
  }
};

}  // namespace

TEST(AnalyticShells, EndMomentLoadHasCorrectDerivatives) {
  test_support::EndMomentTerm term({{0, 1}, {2, 3}}, 4, 0.7);
  const Vector x = Vector::Random(12);
  EXPECT_LT(
      test_support::relative_error(test_support::analytic_gradient(term, x),
                                   test_support::finite_difference_gradient(term, x, 1e-6), 1e-8),
      1e-6);
  EXPECT_LT(
      test_support::relative_error(test_support::assembled_hessian(term, x, false),
                                   test_support::finite_difference_hessian(term, x, 1e-6), 1e-8),
      1e-5);
}

TEST(AnalyticShells, StripUnderEndMomentBendsIntoArcOfRadiusEIOverM) {
  ShellMaterial steel;
  steel.youngs_modulus = 1e8;
  steel.poisson_ratio = 0.0;  // pure cylindrical bending, no anticlastic coupling
  steel.thickness = 1e-3;
  const double length = 1.0;
  ClampedSheet strip(length, 50, 12, steel);
  const double stiffness =
      steel.youngs_modulus * std::pow(steel.thickness, 3) / 12.0 * strip.width;  // EI
  const double radius = 1.2;                                                     // expected
  const double moment = stiffness / radius;                                      // M = EI/R
  std::vector<std::array<int, 2>> ends;
  for (const auto& row : strip.rows) ends.push_back({row[row.size() - 2], row.back()});
  strip.problem->add_term(std::make_unique<test_support::EndMomentTerm>(
      ends, strip.mesh.num_vertices(), moment / strip.rows.size()));
  strip.clamp_and_finalize();
  const Vector x = strip.solve(1e-8);  // tighter stalls at round-off (‖p‖∞ ~ 1e-9)
  double lowest = 1e9, highest = 0.0;
  for (std::size_t j = 0; j < strip.rows.size(); ++j) {
    std::vector<Vec2> arc;
    for (int v : strip.rows[j])
      if (strip.mesh.vertices(v, 0) >= strip.spacing) arc.emplace_back(x[3 * v], x[3 * v + 2]);
    const double fitted = fitted_circle_radius(arc);
    lowest = std::min(lowest, fitted / radius);
    highest = std::max(highest, fitted / radius);
    EXPECT_NEAR(fitted / radius, 1.0, 0.03)
        << "row " << j << ": R = " << fitted << " m, EI/M = " << radius;
  }
  std::cout << "[ strip ] fitted R / (EI/M) over the rows: " << lowest << " to " << highest
            << std::endl;
  // The strip really bent: the free end turned by about (L − a)/R radians.
  const std::vector<int>& row = strip.rows[0];
  const Vec3 end = x.segment<3>(3 * row.back()) - x.segment<3>(3 * row[row.size() - 2]);
  EXPECT_NEAR(std::atan2(end.z(), end.x()), (length - strip.spacing) / radius, 0.03);
}

/// The strip of the previous test, coarser, bent by M = EI/R.
static ClampedSheet bent_strip(double radius) {
  ShellMaterial steel;
  steel.youngs_modulus = 1e8;
  steel.poisson_ratio = 0.0;
  steel.thickness = 1e-3;
  ClampedSheet strip(1.0, 25, 6, steel);
  const double moment =
      steel.youngs_modulus * std::pow(steel.thickness, 3) / 12.0 * strip.width / radius;
  std::vector<std::array<int, 2>> ends;
  for (const auto& row : strip.rows) ends.push_back({row[row.size() - 2], row.back()});
  strip.problem->add_term(std::make_unique<test_support::EndMomentTerm>(
      ends, strip.mesh.num_vertices(), moment / strip.rows.size()));
  strip.clamp_and_finalize();
  return strip;
}

TEST(AnalyticShells, AdaptiveProjectionReachesTheSameEquilibriumInFewerIterations) {
  // Projecting every hinge Hessian drops the geometric stiffness of bent hinges, so projected
  // Newton crawls towards a strongly bent equilibrium; adaptive projection takes exact steps
  // where the Hessian is positive definite. Line-search extrapolation lengthens the projected
  // steps, so it is off for the comparison of projections and compared on its own after.
  ClampedSheet strip = bent_strip(1.2);
  NewtonReport projected, adaptive, extrapolated;
  const Vector x_projected = strip.solve(1e-8, HessianProjection::always, &projected, false);
  const Vector x_adaptive = strip.solve(1e-8, HessianProjection::adaptive, &adaptive, false);
  const Vector x_extrapolated = strip.solve(1e-8, HessianProjection::always, &extrapolated);
  std::cout << "[ projection ] Newton iterations: always " << projected.iterations << ", adaptive "
            << adaptive.iterations << " (" << adaptive.exact_steps << " exact), always with "
            << "extrapolation " << extrapolated.iterations << " ("
            << extrapolated.extrapolated_steps << " extrapolated)" << std::endl;
  EXPECT_EQ(projected.exact_steps, 0);
  EXPECT_GT(adaptive.exact_steps, 0);
  EXPECT_LT(2 * adaptive.iterations, projected.iterations);
  EXPECT_LT(extrapolated.iterations, projected.iterations);
  EXPECT_LT((x_projected - x_adaptive).lpNorm<Eigen::Infinity>(), 1e-5);
  EXPECT_LT((x_projected - x_extrapolated).lpNorm<Eigen::Infinity>(), 1e-5);
}

/// Tip deflection of a plate clamped at x ≤ a and loaded by its weight, over the Euler–Bernoulli
/// value q L⁴ / 8D (ν = 0, so plate and beam theory agree).
static double cantilever_tip_over_theory(int nx, int num_rows) {
  ShellMaterial plate;
  plate.youngs_modulus = 1e11;
  plate.poisson_ratio = 0.0;
  plate.thickness = 1e-3;
  plate.density = 1000.0;
  const double length = 0.5, g = 9.81;
  ClampedSheet cantilever(length, nx, num_rows, plate);
  const TriangleMesh& mesh = cantilever.mesh;
  Eigen::VectorXd masses = Eigen::VectorXd::Zero(mesh.num_vertices());
  const Eigen::VectorXd areas = face_areas(mesh.vertices, mesh.faces);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      masses[mesh.faces(f, k)] += plate.density * plate.thickness * areas[f] / 3.0;
  cantilever.problem->add_term(std::make_unique<Gravity>(masses, Vec3(0, 0, -g)));
  cantilever.clamp_and_finalize();
  const Vector x = cantilever.solve(1e-8);
  const double free_length = length - cantilever.spacing;  // clamped up to x = a
  const double d = plate.youngs_modulus * std::pow(plate.thickness, 3) / 12.0;  // D (ν = 0)
  const double q = plate.density * plate.thickness * g;                         // N/m²
  const double expected = q * std::pow(free_length, 4) / (8.0 * d);             // Euler–Bernoulli
  EXPECT_LT(expected / free_length, 0.05) << "not a small deflection";
  double tip = 0.0;
  for (const auto& row : cantilever.rows) tip += -x[3 * row.back() + 2];
  return tip / cantilever.rows.size() / expected;
}

TEST(AnalyticShells, CantileverPlateTipDeflectionMatchesPlateTheory) {
  // Measured: 1.151 at a = L/25 (6 rows), 1.115 at a = L/50 (12 rows), 1.098 at a = L/100
  // (24 rows): hinge bending is ~10% soft for this varying-curvature load at these
  // resolutions and converges slowly (the uniform-moment strip above is within 3%).
  const double coarse = cantilever_tip_over_theory(25, 6);
  const double fine = cantilever_tip_over_theory(50, 12);
  std::cout << "[ cantilever ] tip / theory: " << coarse << " (a = L/25), " << fine << " (a = L/50)"
            << std::endl;
  EXPECT_LT(std::abs(fine - 1.0), std::abs(coarse - 1.0)) << "does not converge";
  EXPECT_NEAR(fine, 1.0, 0.12);
}

TEST(AnalyticShells, HangingClothReachesEquilibrium) {
  Scene scene = load_scene_file(std::string(PROGSIM_SOURCE_DIR) + "/scenes/hanging_cloth.json");
  scene.mode = StepMode::quasistatic;
  scene.duration = scene.time_step;  // one quasistatic solve
  scene.solver.tolerance = 1e-9;
  scene.solver.max_iterations = 500;
  LevelSimulation sim(scene);
  const StepRecord record = sim.step();
  EXPECT_EQ(record.newton.stop, NewtonStop::converged);
  Vector g;
  sim.problem().gradient(sim.dofs(), g);
  const double weight = sim.model().vertex_masses.sum() * 9.81;
  EXPECT_LT(g.norm(), 1e-6 * weight) << "‖∇E‖ = " << g.norm() << " N, weight " << weight << " N";
  EXPECT_LT(sim.positions().col(1).minCoeff(), 0.5);  // it really sagged
}

TEST(AnalyticShells, WithTheProximalTermOnlyASolveThatDoesNotMoveIsAnEquilibrium) {
  // PSQ eq. 1's proximal term turns each quasistatic solve into a gradient-flow step: its
  // converged minimiser is not an equilibrium of the loads until the step no longer moves.
  // A 1 m cloth of 12 × 12 quads hanging from its top corners; a short step (0.05 s), so the
  // flow takes several solves.
  Scene scene = parse_scene(R"({
    "simulation": {"mode": "quasistatic", "time_step": 0.05, "duration": 0.05},
    "effects": ["membrane", "bending", "gravity"],
    "solver": {"newton_tolerance": 1e-7, "max_newton_iterations": 200},
    "bodies": [{"name": "cloth", "mesh": {"generator": "grid", "width": 1, "height": 1, "nx": 12, "ny": 12},
                "material": {"youngs_modulus": 5e5, "poisson_ratio": 0.3, "thickness": 5e-4,
                             "density": 400}}],
    "handles": [{"body": "cloth", "box": {"min": [-0.01, 0.99, -0.01], "max": [0.01, 1.01, 0.01]}},
                {"body": "cloth", "box": {"min": [0.99, 0.99, -0.01], "max": [1.01, 1.01, 0.01]}}],
    "progressive": {"proximal": true}})",
                            ".");
  LevelSimulation sim(scene);
  const StepRecord first = sim.step();
  ASSERT_EQ(first.newton.stop, NewtonStop::converged);
  EXPECT_FALSE(first.equilibrium) << "the first solve moved the cloth; gravity is not balanced";
  StepRecord last = first;
  for (int k = 0; k < 500 && !last.equilibrium; ++k) last = sim.settle();
  ASSERT_TRUE(last.equilibrium);
  EXPECT_EQ(last.newton.iterations, 0);
  // Independent check: the loads' gradient (the proximal term's vanishes at its own target,
  // the state) is balanced, and a solve without the proximal term stays where the flow ended.
  Vector g;
  sim.problem().gradient(sim.dofs(), g);
  const double weight = sim.model().vertex_masses.sum() * 9.81;
  EXPECT_LT(g.norm(), 1e-3 * weight) << "‖∇E‖ = " << g.norm() << " N, weight " << weight << " N";
  scene.progressive.proximal = false;
  LevelSimulation direct(scene);
  ASSERT_TRUE(direct.step().equilibrium);
  const double distance = (direct.positions() - sim.positions()).rowwise().norm().maxCoeff();
  EXPECT_LT(distance, 1e-3) << "max vertex distance, m";
}

TEST(AnalyticShells, BalloonFollowsNeoHookeanPressureStretchCurve) {
  const Scene scene = load_scene_file(std::string(PROGSIM_SOURCE_DIR) + "/scenes/balloon.json");
  LevelSimulation sim(scene);
  for (int s = 0; s < scene.num_steps(); ++s)
    ASSERT_EQ(sim.step().newton.stop, NewtonStop::converged);
  const Body& body = scene.bodies[0];
  const ShellMaterial& m = body.material;
  // Uniform stretch s of the rest polyhedron (area A, volume V): equilibrium of
  // A t W(s) − p V s³ gives p = A t W'(s) / (3 V s²), W'(s) = μ(2s − 2/s) + 4λ ln s / s.
  const double area = face_areas(body.mesh.vertices, body.mesh.faces).sum();
  double volume = 0.0;
  for (int f = 0; f < body.mesh.num_faces(); ++f) {
    const Vec3 a = body.mesh.vertices.row(body.mesh.faces(f, 0)),
               b = body.mesh.vertices.row(body.mesh.faces(f, 1)),
               c = body.mesh.vertices.row(body.mesh.faces(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  const double mu = shear_modulus(m), lambda = plane_stress_lambda(m);
  const auto pressure_at = [&](double s) {
    const double dw = mu * (2 * s - 2 / s) + 4 * lambda * std::log(s) / s;
    return area * m.thickness * dw / (3 * volume * s * s);
  };
  const Vec3 centre = sim.positions().colwise().mean();
  const double stretch =
      (sim.positions().rowwise() - centre.transpose()).rowwise().norm().mean() / 0.1;
  EXPECT_GT(stretch, 1.05);
  EXPECT_NEAR(pressure_at(stretch) / body.pressure, 1.0, 0.02) << "stretch " << stretch;
}
