// Problem: reduced gradient and Hessian against a dense assembly done independently here.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "energy/gravity.hpp"
#include "energy/inertia.hpp"
#include "problem/problem.hpp"
#include "support/energy_checks.hpp"
#include "support/spring_term.hpp"

using namespace progsim;
using progsim::test_support::SpringTerm;

namespace {

Problem make_problem(const std::vector<bool>& fixed) {
  Problem problem(12);
  problem.add_term(std::make_unique<SpringTerm>(
      std::vector<std::array<int, 2>>{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}}, 4, 3.0));
  problem.add_term(std::make_unique<Gravity>(Eigen::Vector4d(1, 2, 3, 4), Vec3(0, -9.81, 0)));
  problem.add_term(std::make_unique<Inertia>(Eigen::Vector4d(1, 2, 3, 4), 0.1));
  problem.set_fixed_dofs(fixed);
  problem.finalize();
  return problem;
}

}  // namespace

TEST(Problem, ReducedHessianEqualsDenseAssemblyRestrictedToFreeDofs) {
  std::vector<bool> fixed(12, false);
  fixed[0] = fixed[1] = fixed[2] = fixed[7] = true;
  Problem problem = make_problem(fixed);
  const Vector x = Vector::Random(12);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(12, 12);
  for (const auto& term : problem.terms()) dense += test_support::assembled_hessian(*term, x, true);
  std::vector<int> free;
  for (int d = 0; d < 12; ++d)
    if (!fixed[d]) free.push_back(d);
  Eigen::MatrixXd expected(free.size(), free.size());
  for (std::size_t r = 0; r < free.size(); ++r)
    for (std::size_t c = 0; c < free.size(); ++c) expected(r, c) = dense(free[r], free[c]);
  const Eigen::MatrixXd lower = Eigen::MatrixXd(problem.hessian(x, true));
  const Eigen::MatrixXd full =
      lower + lower.transpose() - Eigen::MatrixXd(lower.diagonal().asDiagonal());
  EXPECT_EQ(problem.num_free(), 8);
  EXPECT_LT((full - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Problem, GradientIsZeroOnFixedDofsAndMatchesFiniteDifferences) {
  std::vector<bool> fixed(12, false);
  fixed[4] = true;
  Problem problem = make_problem(fixed);
  const Vector x = Vector::Random(12);
  Vector g;
  problem.gradient(x, g);
  EXPECT_EQ(g[4], 0.0);
  for (int d = 0; d < 12; ++d) {
    if (d == 4) continue;
    Vector xp = x, xm = x;
    xp[d] += 1e-6;
    xm[d] -= 1e-6;
    EXPECT_NEAR(g[d], (problem.value(xp) - problem.value(xm)) / 2e-6, 1e-6) << "dof " << d;
  }
}

TEST(Problem, CountsEvaluationsPerTerm) {
  Problem problem = make_problem(std::vector<bool>(12, false));
  const Vector x = Vector::Zero(12);
  Vector g;
  problem.value(x);
  problem.value(x);
  problem.gradient(x, g);
  problem.hessian(x, false);
  ASSERT_EQ(problem.term_stats().size(), 3u);
  for (const TermStats& s : problem.term_stats()) {
    EXPECT_EQ(s.value_evaluations, 2);
    EXPECT_EQ(s.gradient_evaluations, 1);
    EXPECT_EQ(s.hessian_evaluations, 1);
  }
  EXPECT_STREQ(problem.terms()[0]->name(), "springs");
}

TEST(Problem, RejectsWrongMaskSizeAndLateTerms) {
  Problem problem = make_problem(std::vector<bool>(12, false));
  EXPECT_THROW(problem.set_fixed_dofs(std::vector<bool>(5, false)), Error);
  EXPECT_THROW(problem.add_term(std::make_unique<Gravity>(Eigen::Vector4d::Ones(), Vec3::Zero())),
               Error);
}
