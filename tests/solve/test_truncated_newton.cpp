// Truncated Newton directions: CG against Eigen's dense solve on a definite system, and the
// negative-curvature stops of Nocedal & Wright's Algorithm 7.1 on indefinite ones.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "solve/truncated_newton.hpp"

using namespace progsim;
using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

namespace {

Sparse lower(const Eigen::MatrixXd& dense) {
  Sparse s = dense.sparseView();
  s = Sparse(s.triangularView<Eigen::Lower>());
  s.makeCompressed();
  return s;
}

/// The factorization of `dense` (definite) as a preconditioner.
void factorize(const Eigen::MatrixXd& dense, SparseCholesky& m) {
  const Sparse s = lower(dense);
  m.analyze(s);
  ASSERT_TRUE(m.factorize(s, false));
}

/// A symmetric matrix with the given eigenvalues in a fixed random orthonormal basis.
Eigen::MatrixXd with_eigenvalues(const Eigen::VectorXd& lambda) {
  std::srand(7);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(lambda.size(), lambda.size());
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  const Eigen::MatrixXd q = qr.householderQ();
  return q * lambda.asDiagonal() * q.transpose();
}

/// Soft modes (eigenvalues 1e-3) that a stiffer preconditioner overestimates, as projection
/// does, and a gradient with components along every mode.
struct SoftSystem {
  Eigen::MatrixXd h = with_eigenvalues(
      (Eigen::VectorXd(8) << 1e-3, 2e-3, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0).finished());
  Eigen::MatrixXd stiffer = h + 0.5 * Eigen::MatrixXd::Identity(8, 8);
  Vector g = Vector::LinSpaced(8, -1.0, 2.0);
  SparseCholesky m;  ///< the factorized stiffer matrix
  SoftSystem() { factorize(stiffer, m); }
};

}  // namespace

TEST(TruncatedNewton, ReachesTheNewtonStepOfADefiniteSystem) {
  // CG recovers the exact step of the soft system that Eigen's dense LDLT gives.
  SoftSystem soft;
  const Eigen::MatrixXd &h = soft.h, &stiffer = soft.stiffer;
  const Vector& g = soft.g;
  const SparseCholesky& m = soft.m;
  Vector p, work[4];
  TruncatedNewtonSettings settings;
  settings.relative_residual = 1e-12;
  const TruncatedNewtonStats stats = truncated_newton_step(lower(h), m, g, settings, p, work);
  const Vector newton = h.ldlt().solve(-g);
  EXPECT_FALSE(stats.negative_curvature);
  EXPECT_LE(stats.iterations, 8);  // CG is exact after n steps in exact arithmetic
  EXPECT_LT((p - newton).norm(), 1e-8 * newton.norm());
  Vector preconditioned;
  m.solve(-g, preconditioned);
  EXPECT_GT(p.norm(), 10.0 * preconditioned.norm());  // the soft modes were underestimated
}

TEST(TruncatedNewton, StopsAtTheForcingTerm) {
  Eigen::VectorXd lambda(6);
  lambda << 0.01, 0.1, 1.0, 3.0, 10.0, 30.0;
  const Eigen::MatrixXd h = with_eigenvalues(lambda);
  SparseCholesky m;
  factorize(Eigen::MatrixXd::Identity(6, 6), m);
  const Vector g = Vector::Ones(6);
  Vector p, work[4];
  const TruncatedNewtonStats stats = truncated_newton_step(lower(h), m, g, {}, p, work);
  const double residual = (h * p + g).norm() / g.norm();
  EXPECT_LE(residual, 0.1);
  EXPECT_NEAR(stats.relative_residual, residual, 1e-12);
  EXPECT_GT(stats.iterations, 1);
}

TEST(TruncatedNewton, FallsBackToThePreconditionedStepOnNegativeCurvature) {
  // H negative definite: the first CG direction already has negative curvature.
  const Eigen::MatrixXd h = -with_eigenvalues(Eigen::VectorXd::LinSpaced(5, 1.0, 5.0));
  const Eigen::MatrixXd preconditioner = 2.0 * Eigen::MatrixXd::Identity(5, 5);
  SparseCholesky m;
  factorize(preconditioner, m);
  const Vector g = Vector::LinSpaced(5, 1.0, -3.0);
  Vector p, work[4];
  const TruncatedNewtonStats stats = truncated_newton_step(lower(h), m, g, {}, p, work);
  EXPECT_TRUE(stats.negative_curvature);
  EXPECT_EQ(stats.iterations, 0);
  EXPECT_LT((p + 0.5 * g).norm(), 1e-12);
}

TEST(TruncatedNewton, KeepsADescentIterateWhenCurvatureTurnsNegativeLater) {
  // Two positive and one strongly negative eigenvalue; the gradient lies mostly in the
  // positive directions, so CG takes a step before it meets the negative one.
  Eigen::VectorXd lambda(3);
  lambda << 1.0, 2.0, -50.0;
  const Eigen::MatrixXd h = with_eigenvalues(lambda);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(h);
  const Vector g = 3.0 * eig.eigenvectors().col(2) + 1.0 * eig.eigenvectors().col(1) +
                   0.05 * eig.eigenvectors().col(0);  // columns sorted: −50, 1, 2
  SparseCholesky m;
  factorize(Eigen::MatrixXd::Identity(3, 3), m);
  Vector p, work[4];
  TruncatedNewtonSettings settings;
  settings.relative_residual = 1e-12;
  const TruncatedNewtonStats stats = truncated_newton_step(lower(h), m, g, settings, p, work);
  EXPECT_TRUE(stats.negative_curvature);
  EXPECT_GE(stats.iterations, 1);
  EXPECT_LT(g.dot(p), 0.0);  // a descent direction for the line search
}

TEST(TruncatedNewton, StaysInsideTheTrustRegion) {
  // The soft system, whose Newton step is hundreds of times longer than the
  // preconditioned one: with Δ = 3 the step stops on the boundary ‖p‖_M = 3‖M⁻¹g‖_M, still
  // a descent direction; with Δ = 1 it is the preconditioned step itself.
  SoftSystem soft;
  const Eigen::MatrixXd &h = soft.h, &stiffer = soft.stiffer;
  const Vector& g = soft.g;
  const SparseCholesky& m = soft.m;
  const Vector preconditioned = stiffer.ldlt().solve(-g);
  auto m_norm = [&](const Vector& v) { return std::sqrt(v.dot(stiffer * v)); };
  Vector p, work[4];
  TruncatedNewtonSettings settings;
  settings.relative_residual = 1e-12;
  settings.radius = 3.0;
  TruncatedNewtonStats stats = truncated_newton_step(lower(h), m, g, settings, p, work);
  EXPECT_TRUE(stats.on_boundary);
  EXPECT_NEAR(m_norm(p), 3.0 * m_norm(preconditioned), 1e-9 * m_norm(p));
  EXPECT_NEAR(stats.length, 3.0, 1e-9);
  EXPECT_LT(g.dot(p), 0.0);
  settings.radius = 1.0;
  stats = truncated_newton_step(lower(h), m, g, settings, p, work);
  EXPECT_TRUE(stats.on_boundary);
  EXPECT_LT((p - preconditioned).norm(), 1e-9 * preconditioned.norm());
}
