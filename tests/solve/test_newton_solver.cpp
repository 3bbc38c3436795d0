// Projected Newton: exact on quadratics, stop reasons, diagonal shift on singular systems.
#include <gtest/gtest.h>

#include "energy/gravity.hpp"
#include "problem/problem.hpp"
#include "solve/newton_solver.hpp"
#include "support/spring_term.hpp"

using namespace progsim;
using progsim::test_support::SpringTerm;

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
  std::vector<bool> fixed(3 * n, false);
  fixed[0] = fixed[1] = fixed[2] = true;
  problem.set_fixed_dofs(fixed);
  problem.finalize();
  Vector x = Vector::Zero(3 * n);
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, NewtonSettings{}, 1.0, 1.0);
  EXPECT_EQ(report.stop, NewtonStop::converged);
  EXPECT_LE(report.iterations, 2);
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
  Vector x(9);
  x << 0, 0, 0, 1, 0, 0, 3, 0, 0;
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, NewtonSettings{}, 1.0, 1.0);
  EXPECT_EQ(report.stop, NewtonStop::converged);
  EXPECT_GT(report.max_shift, 0.0);
  EXPECT_NEAR((x.segment<3>(0) - x.segment<3>(6)).norm(), 0.0, 1e-6);
}

TEST(NewtonSolver, ReportsTheIterationCap) {
  Problem problem(6);
  problem.add_term(std::make_unique<SpringTerm>(std::vector<std::array<int, 2>>{{0, 1}}, 2, 1.0));
  std::vector<bool> fixed(6, false);
  fixed[0] = fixed[1] = fixed[2] = true;
  problem.set_fixed_dofs(fixed);
  problem.finalize();
  Vector x = Vector::Ones(6);
  x.head<3>().setZero();
  NewtonSettings settings;
  settings.max_iterations = 0;
  NewtonSolver solver;
  EXPECT_EQ(solver.minimize(problem, x, settings, 1.0, 1.0).stop, NewtonStop::max_iterations);
  EXPECT_STREQ(stop_name(NewtonStop::line_search_failed), "line_search_failed");
}
