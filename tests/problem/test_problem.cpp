// Problem: reduced gradient and Hessian against a dense assembly done independently here.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "energy/changing_pattern_term.hpp"
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

namespace {

/// E(x₀ + S z) for the 12-DOF problem with DOFs {3, 6} and {5, 8, 11} tied and DOF 0 fixed:
/// S maps the 9 unknowns (free DOFs in order, a group at its smallest DOF) to the DOFs.
Eigen::MatrixXd tied_selection() {
  const std::vector<int> unknown = {-1, 0, 1, 2, 3, 4, 2, 5, 4, 6, 7, 4};  // per DOF
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(12, 8);
  for (int d = 0; d < 12; ++d)
    if (unknown[d] >= 0) s(d, unknown[d]) = 1.0;
  return s;
}

}  // namespace

TEST(Problem, SharedDofsReduceToSelectionTransposeTimesGradientAndHessian) {
  std::vector<bool> fixed(12, false);
  fixed[0] = true;
  Problem problem(12);
  problem.add_term(std::make_unique<SpringTerm>(
      std::vector<std::array<int, 2>>{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}}, 4, 3.0));
  problem.add_term(std::make_unique<Inertia>(Eigen::Vector4d(1, 2, 3, 4), 0.1));
  problem.set_fixed_dofs(fixed);
  problem.set_shared_dofs({{3, 6}, {5, 8, 11}});
  problem.finalize();
  ASSERT_EQ(problem.num_free(), 8);
  const Eigen::MatrixXd s = tied_selection();
  const Vector x = Vector::Random(12);
  // Independent check: central differences of z ↦ E(x + S z) at z = 0.
  const auto energy_at = [&](const Vector& z) { return problem.value(Vector(x + s * z)); };
  Vector g_full, g;
  problem.gradient(x, g_full);
  problem.restrict_to_free(g_full, g);
  const double eps = 1e-3;
  Eigen::MatrixXd expected_hessian(8, 8);
  for (int i = 0; i < 8; ++i) {
    const Vector ei = eps * Vector::Unit(8, i);
    EXPECT_NEAR(g[i], (energy_at(ei) - energy_at(-ei)) / (2 * eps), 1e-4 * (1 + std::abs(g[i])))
        << "unknown " << i;
    for (int j = 0; j < 8; ++j) {
      const Vector ej = eps * Vector::Unit(8, j);
      expected_hessian(i, j) =
          (energy_at(ei + ej) - energy_at(ei - ej) - energy_at(-ei + ej) + energy_at(-ei - ej)) /
          (4 * eps * eps);
    }
  }
  const Eigen::MatrixXd lower = Eigen::MatrixXd(problem.hessian(x, false));
  const Eigen::MatrixXd full =
      lower + lower.transpose() - Eigen::MatrixXd(lower.diagonal().asDiagonal());
  EXPECT_LT((full - expected_hessian).cwiseAbs().maxCoeff(),
            1e-5 * expected_hessian.cwiseAbs().maxCoeff());
  // A step moves every DOF of a group alike and leaves the fixed one.
  Vector step;
  problem.expand_from_free(Vector::LinSpaced(8, 1, 8), step);
  EXPECT_EQ(step[0], 0.0);
  EXPECT_EQ(step[3], step[6]);
  EXPECT_EQ(step[5], step[8]);
  EXPECT_EQ(step[5], step[11]);
  EXPECT_TRUE(step.isApprox(s * Vector::LinSpaced(8, 1, 8)));
}

TEST(Problem, RejectsSharedDofsThatAreFixedRepeatedOrOutOfRange) {
  std::vector<bool> fixed(12, false);
  fixed[0] = true;
  Problem problem = make_problem(fixed);
  EXPECT_THROW(problem.set_shared_dofs({{0, 1}}), Error);
  EXPECT_THROW(problem.set_shared_dofs({{1, 2}, {2, 3}}), Error);
  EXPECT_THROW(problem.set_shared_dofs({{1, 12}}), Error);
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

namespace {

/// Springs between the vertex pairs switched on, a stand-in for contact: a term whose Hessian
/// pattern changes with the set of pairs (E = Σ k/2 ‖x_a − x_b‖² over the switched-on pairs).
class SwitchedSprings : public ChangingPatternTerm {
 public:
  explicit SwitchedSprings(double stiffness) : k_(stiffness) {}
  const char* name() const override { return "switched springs"; }
  std::vector<std::array<int, 2>> on;
  double value(const Vector& x) const override {
    double e = 0;
    for (const auto& [a, b] : on)
      e += 0.5 * k_ * (x.segment<3>(3 * a) - x.segment<3>(3 * b)).squaredNorm();
    return e;
  }
  void add_gradient(const Vector& x, Vector& g) const override {
    for (const auto& [a, b] : on) {
      const Vec3 d = k_ * (x.segment<3>(3 * a) - x.segment<3>(3 * b));
      g.segment<3>(3 * a) += d;
      g.segment<3>(3 * b) -= d;
    }
  }
  void append_hessian_triplets(const Vector&, bool,
                               std::vector<Eigen::Triplet<double>>& out) const override {
    for (const auto& [a, b] : on)
      for (int r = 0; r < 3; ++r) {
        out.emplace_back(3 * a + r, 3 * a + r, k_);
        out.emplace_back(3 * b + r, 3 * b + r, k_);
        out.emplace_back(3 * a + r, 3 * b + r, -k_);
        out.emplace_back(3 * b + r, 3 * a + r, -k_);
      }
  }

 private:
  double k_;
};

/// The full symmetric matrix from the lower triangle Problem::hessian() stores.
Eigen::MatrixXd symmetric(const Problem::SparseMatrix& lower) {
  const Eigen::MatrixXd l(lower);
  return l + l.transpose() - Eigen::MatrixXd(l.diagonal().asDiagonal());
}

/// k I on the diagonal blocks of a and b, −k I off them, for every pair switched on; plus the
/// springs' 1 N/m on the chain 0–1–2–…: the Hessian written out by hand, 3 DOFs per vertex.
Eigen::MatrixXd expected_hessian(const std::vector<std::array<int, 2>>& on, double k,
                                 int num_vertices) {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(3 * num_vertices, 3 * num_vertices);
  auto add = [&](int a, int b, double s) {
    const Eigen::Matrix3d i = s * Eigen::Matrix3d::Identity();
    h.block<3, 3>(3 * a, 3 * a) += i;
    h.block<3, 3>(3 * b, 3 * b) += i;
    h.block<3, 3>(3 * a, 3 * b) -= i;
    h.block<3, 3>(3 * b, 3 * a) -= i;
  };
  for (int v = 0; v + 1 < num_vertices; ++v) add(v, v + 1, 1.0);
  for (const auto& [a, b] : on) add(a, b, k);
  return h;
}

}  // namespace

TEST(Problem, ChangingPatternKeepsItsAnalysisWhileASolveReusesEntries) {
  constexpr int kVertices = 8;
  Problem problem(3 * kVertices);
  std::vector<std::array<int, 2>> chain;
  for (int v = 0; v + 1 < kVertices; ++v) chain.push_back({v, v + 1});
  problem.add_term(std::make_unique<SpringTerm>(chain, kVertices, 1.0));
  SwitchedSprings& contact = problem.add_term(std::make_unique<SwitchedSprings>(5.0));
  problem.finalize();
  const Vector x = Vector::Random(3 * kVertices);
  auto check = [&](const char* when) {
    EXPECT_LT((symmetric(problem.hessian(x, false)) - expected_hessian(contact.on, 5.0, kVertices))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12)
        << when;
  };
  problem.begin_solve(x);
  contact.on = {{0, 5}, {2, 7}};
  check("two pairs");
  const long first = problem.pattern_version();
  contact.on = {{2, 7}};
  check("one pair gone");
  contact.on = {{0, 5}, {2, 7}};
  check("back again");
  EXPECT_EQ(problem.pattern_version(), first) << "entries already held need no new analysis";
  contact.on.clear();  // every pair of vertices not joined by the chain: 21 new blocks
  for (int a = 0; a < kVertices; ++a)
    for (int b = a + 2; b < kVertices; ++b) contact.on.push_back({a, b});
  check("new pairs");
  const long grown = problem.pattern_version();
  EXPECT_NE(grown, first);

  problem.begin_solve(x);  // the next solve still uses every entry: same pattern
  check("next solve, same pairs");
  EXPECT_EQ(problem.pattern_version(), grown);
  const Eigen::Index full = problem.hessian(x, false).nonZeros();

  problem.begin_solve(x);  // no contact pair left: a third of the entries unused, dropped
  contact.on.clear();
  check("no pairs");
  EXPECT_NE(problem.pattern_version(), grown);
  EXPECT_LT(problem.hessian(x, false).nonZeros(), full);
}

TEST(Problem, ChangingPatternAfterEveryDofIsFixedHasAnEmptyHessian) {
  // finalize() again (every DOF now fixed) must forget the slots of the earlier pattern.
  Problem problem(3 * 4);
  SwitchedSprings& contact = problem.add_term(std::make_unique<SwitchedSprings>(5.0));
  problem.finalize();
  const Vector x = Vector::Random(12);
  contact.on = {{0, 2}, {1, 3}};
  problem.begin_solve(x);
  EXPECT_EQ(problem.hessian(x, false).nonZeros(), 12 + 6);  // diagonal + two off blocks
  problem.set_fixed_dofs(std::vector<bool>(12, true));
  problem.begin_solve(x);
  EXPECT_EQ(problem.hessian(x, false).rows(), 0);
  problem.set_fixed_dofs(std::vector<bool>(12, false));
  problem.begin_solve(x);
  EXPECT_LT((symmetric(problem.hessian(x, false)) - expected_hessian(contact.on, 5.0, 4) +
             expected_hessian({}, 0.0, 4))
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
}
