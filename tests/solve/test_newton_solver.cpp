// Projected Newton: exact on quadratics, stop reasons, diagonal shift on singular systems,
// line-search extrapolation out of a saddle, within what the step filters admit.
#include <gtest/gtest.h>

#include <iostream>
#include <limits>

#include "energy/gravity.hpp"
#include "problem/problem.hpp"
#include "solve/newton_solver.hpp"
#include "solve/step_filter.hpp"
#include "support/spring_term.hpp"

using namespace progsim;
using progsim::test_support::SpringTerm;

namespace {

/// E = Σ_i −c/2 ‖x_i‖² + ¼ ‖x_i‖⁴: concave at the origin, so per-element projection clamps
/// its Hessian there to zero and projected Newton's steps leave the origin too slowly.
class SaddleWell : public StencilTerm<1> {
 public:
  SaddleWell(int vertex, int num_vertices, double c)
      : StencilTerm<1>({{vertex}}, num_vertices), c_(c) {}
  const char* name() const override { return "saddle_well"; }

 protected:
  double element_value(int, const LocalVector& u) const override {
    const double r2 = u.squaredNorm();
    return -0.5 * c_ * r2 + 0.25 * r2 * r2;
  }
  void element_gradient(int, const LocalVector& u, LocalVector& g) const override {
    g = (u.squaredNorm() - c_) * u;
  }
  void element_hessian(int, const LocalVector& u, LocalMatrix& h) const override {
    h = (u.squaredNorm() - c_) * LocalMatrix::Identity() + 2.0 * u * u.transpose();
  }

 private:
  double c_;
};

/// Admits only steps that keep one vertex inside the ball ‖x_v‖ ≤ radius (a stand-in for CCD);
/// no energy of its own.
class BallFilter : public EnergyTerm, public StepFilter {
 public:
  BallFilter(int vertex, double radius) : vertex_(vertex), radius_(radius) {}
  const char* name() const override { return "ball"; }
  double value(const Vector&) const override { return 0.0; }
  void add_gradient(const Vector&, Vector&) const override {}
  std::size_t hessian_entry_count() const override { return 0; }
  void hessian_pattern(int*, int*) const override {}
  void hessian_values(const Vector&, bool, double*) const override {}
  void begin_solve(const Vector&) override {}
  bool end_iteration(const Vector&) override { return false; }
  /// The ball is convex, so the segment stays inside while its end does: the root of
  /// ‖x + αp‖ = radius, with a 1 % margin as CCD keeps one.
  double max_step(const Vector& x, const Vector& p) override {
    const Vec3 a = x.segment<3>(3 * vertex_), d = p.segment<3>(3 * vertex_);
    if ((a + d).norm() <= radius_) return 1.0;
    const double dd = d.squaredNorm(), ad = a.dot(d), rest = radius_ * radius_ - a.squaredNorm();
    return 0.99 * (-ad + std::sqrt(ad * ad + dd * rest)) / dd;
  }

 private:
  int vertex_;
  double radius_;
};

/// A step filter that cannot bound any step: what CCD returns for a non-finite motion.
class NanFilter : public BallFilter {
 public:
  NanFilter() : BallFilter(1, 1.0) {}
  double max_step(const Vector&, const Vector&) override {
    return std::numeric_limits<double>::quiet_NaN();
  }
};

/// Fixes vertex 0 (its three DOFs) and finalizes the problem.
void fix_vertex_zero_and_finalize(Problem& problem) {
  std::vector<bool> fixed(problem.num_dofs(), false);
  fixed[0] = fixed[1] = fixed[2] = true;
  problem.set_fixed_dofs(fixed);
  problem.finalize();
}

/// Three vertices on the x axis at 0, 1 and 3.
Vector three_on_a_line() {
  Vector x(9);
  x << 0, 0, 0, 1, 0, 0, 3, 0, 0;
  return x;
}

/// Vertex 0 fixed at the origin, vertex 1 free just off it, a unit spring between them and a
/// saddle well of depth c = 2 on vertex 1: E(r) = −r²/2 + r⁴/4, minimal at ‖x₁‖ = 1.
Problem saddle_problem(double filter_radius) {
  Problem problem(6);
  problem.add_term(std::make_unique<SpringTerm>(std::vector<std::array<int, 2>>{{0, 1}}, 2, 1.0));
  problem.add_term(std::make_unique<SaddleWell>(1, 2, 2.0));
  if (filter_radius > 0.0) problem.add_term(std::make_unique<BallFilter>(1, filter_radius));
  fix_vertex_zero_and_finalize(problem);
  return problem;
}

Vector just_off_the_origin() {
  Vector x = Vector::Zero(6);
  x[3] = 1e-6;
  return x;
}

/// A tolerance below the start's distance from the origin (the first step is about as long).
NewtonSettings saddle_settings() {
  NewtonSettings settings;
  settings.tolerance = 1e-10;
  return settings;
}

}  // namespace

TEST(NewtonSolver, ExtrapolatesOutOfASaddleToTheAnalyticMinimum) {
  // Projected steps only double ‖x₁‖ near the origin (about 20 iterations to leave it);
  // extrapolation doubles α instead while the energy falls.
  NewtonReport report[2];
  for (bool extrapolate : {false, true}) {
    Problem problem = saddle_problem(0.0);
    Vector x = just_off_the_origin();
    NewtonSettings settings = saddle_settings();
    settings.extrapolate = extrapolate;
    NewtonSolver solver;
    report[extrapolate] = solver.minimize(problem, x, settings, 1.0, 1.0);
    EXPECT_EQ(report[extrapolate].stop, NewtonStop::converged) << "extrapolate " << extrapolate;
    EXPECT_NEAR(x[3], 1.0, 1e-8) << "extrapolate " << extrapolate;
  }
  std::cout << "[ saddle ] Newton iterations: " << report[0].iterations << " projected, "
            << report[1].iterations << " extrapolated (" << report[1].extrapolated_steps
            << " steps lengthened)" << std::endl;
  EXPECT_EQ(report[0].extrapolated_steps, 0);
  EXPECT_GT(report[1].extrapolated_steps, 0);
  EXPECT_LE(2 * report[1].iterations, report[0].iterations)
      << report[1].iterations << " iterations with extrapolation, " << report[0].iterations
      << " without";
}

TEST(NewtonSolver, NeverExtrapolatesPastWhatTheStepFiltersAdmit) {
  // The minimum (‖x₁‖ = 1) lies beyond the filter's ball of radius 0.5: unfiltered doublings
  // would overshoot it from ‖x₁‖ ≈ 1e-3 in one step.
  Problem problem = saddle_problem(0.5);
  Vector x = just_off_the_origin();
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, saddle_settings(), 1.0, 1.0);
  EXPECT_GT(report.extrapolated_steps, 0);
  EXPECT_LE(x.segment<3>(3).norm(), 0.5);
  EXPECT_GT(x[3], 0.4);  // it did move out to the ball's edge
}

TEST(NewtonSolver, StopsAsNonFiniteWhenAStepFilterCannotBoundTheStep) {
  // Issue 33 §7: std::min(α, NaN) kept α, so a NaN CCD bound admitted the whole step.
  Problem problem(6);
  problem.add_term(std::make_unique<SpringTerm>(std::vector<std::array<int, 2>>{{0, 1}}, 2, 1.0));
  problem.add_term(std::make_unique<SaddleWell>(1, 2, 2.0));
  problem.add_term(std::make_unique<NanFilter>());
  fix_vertex_zero_and_finalize(problem);
  Vector x = just_off_the_origin();
  const Vector start = x;
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, saddle_settings(), 1.0, 1.0);
  EXPECT_EQ(report.stop, NewtonStop::non_finite);
  EXPECT_EQ(x, start);  // nothing taken
}

TEST(NewtonSolver, SolvesAQuadraticInOneStepToTheAnalyticEquilibrium) {
  // A chain of springs hanging from vertex 0: vertex i sits below vertex i−1 by the weight
  // of everything below it divided by k (linear springs, zero rest length).
  const int n = 6;
  const double k = 50.0, m = 0.2, g = 9.81;
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i + 1 < n; ++i) pairs.push_back({i, i + 1});
  Problem problem(3 * n);
  problem.add_term(std::make_unique<SpringTerm>(pairs, n, k));
  problem.add_term(std::make_unique<Gravity>(Eigen::VectorXd::Constant(n, m), Vec3(0, -g, 0)));
  fix_vertex_zero_and_finalize(problem);
  Vector x = Vector::Zero(3 * n);
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, NewtonSettings{}, 1.0, 1.0);
  EXPECT_EQ(report.stop, NewtonStop::converged);
  EXPECT_LE(report.iterations, 2);
  EXPECT_EQ(report.extrapolated_steps, 0);  // the model is exact: ρ = 1
  double y = 0.0;
  for (int i = 1; i < n; ++i) {
    y -= (n - i) * m * g / k;
    EXPECT_NEAR(x[3 * i + 1], y, 1e-10) << "vertex " << i;
    EXPECT_NEAR(x[3 * i], 0.0, 1e-12);
  }
}

TEST(NewtonSolver, ShiftsTheDiagonalWhenTheHessianIsSingular) {
  // Free springs without any anchor: translations are a null space of the Hessian.
  Problem problem(9);
  problem.add_term(
      std::make_unique<SpringTerm>(std::vector<std::array<int, 2>>{{0, 1}, {1, 2}}, 3, 1.0));
  problem.finalize();
  Vector x = three_on_a_line();
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, NewtonSettings{}, 1.0, 1.0);
  EXPECT_EQ(report.stop, NewtonStop::converged);
  EXPECT_GT(report.max_shift, 0.0);
  EXPECT_NEAR((x.segment<3>(0) - x.segment<3>(6)).norm(), 0.0, 1e-6);
}

TEST(NewtonSolver, NeverTakesUnprojectedStepsOfAStandInHessian) {
  // The same definite springs, once declaring their Hessian exact and once a stand-in (as the
  // PSQ proxy's is): adaptive projection factorizes the unprojected Hessian only in the first.
  struct StandInSprings : SpringTerm {
    using SpringTerm::SpringTerm;
    bool hessian_is_exact() const override { return false; }
  };
  for (bool stand_in : {false, true}) {
    Problem problem(9);
    const std::vector<std::array<int, 2>> pairs{{0, 1}, {1, 2}};
    if (stand_in)
      problem.add_term(std::make_unique<StandInSprings>(pairs, 3, 1.0));
    else
      problem.add_term(std::make_unique<SpringTerm>(pairs, 3, 1.0));
    fix_vertex_zero_and_finalize(problem);
    Vector x = three_on_a_line();
    NewtonSolver solver;
    const NewtonReport report = solver.minimize(problem, x, NewtonSettings{}, 1.0, 1.0);
    EXPECT_EQ(report.stop, NewtonStop::converged);
    EXPECT_EQ(report.exact_steps > 0, !stand_in) << "stand-in " << stand_in;
  }
}

TEST(NewtonSolver, ReportsTheIterationCap) {
  Problem problem(6);
  problem.add_term(std::make_unique<SpringTerm>(std::vector<std::array<int, 2>>{{0, 1}}, 2, 1.0));
  fix_vertex_zero_and_finalize(problem);
  Vector x = Vector::Ones(6);
  x.head<3>().setZero();
  NewtonSettings settings;
  settings.max_iterations = 0;
  NewtonSolver solver;
  EXPECT_EQ(solver.minimize(problem, x, settings, 1.0, 1.0).stop, NewtonStop::max_iterations);
  EXPECT_STREQ(stop_name(NewtonStop::line_search_failed), "line_search_failed");
}

TEST(NewtonSolver, StopsWhenItsInterruptCheckSaysSoAtTheLastAcceptedIterate) {
  // The saddle needs about 20 projected iterations; the check says stop at its 4th call, so
  // the solve returns after 3 iterations, where a 3-iteration cap leaves it.
  NewtonSettings settings = saddle_settings();
  settings.extrapolate = false;
  Problem capped_problem = saddle_problem(0.0);
  Vector capped = just_off_the_origin();
  settings.max_iterations = 3;
  NewtonSolver capped_solver;
  const NewtonReport cap = capped_solver.minimize(capped_problem, capped, settings, 1.0, 1.0);
  ASSERT_EQ(cap.stop, NewtonStop::max_iterations);

  Problem problem = saddle_problem(0.0);
  Vector x = just_off_the_origin();
  settings.max_iterations = 100;
  NewtonSolver solver;
  int checks = 0;
  solver.set_interrupt([&] { return ++checks > 3; });
  const NewtonReport report = solver.minimize(problem, x, settings, 1.0, 1.0);
  EXPECT_EQ(report.stop, NewtonStop::interrupted);
  EXPECT_EQ(report.iterations, 3);
  EXPECT_EQ(x, capped);
  EXPECT_DOUBLE_EQ(report.gradient_norm, cap.gradient_norm);  // of the state returned
  EXPECT_STREQ(stop_name(NewtonStop::interrupted), "interrupted");
  solver.set_interrupt({});  // cleared: the next solve runs on to the minimum
  EXPECT_EQ(solver.minimize(problem, x, settings, 1.0, 1.0).stop, NewtonStop::converged);
  EXPECT_NEAR(x[3], 1.0, 1e-8);
}
