#include "support/energy_checks.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <vector>

namespace progsim::test_support {

Vector finite_difference_gradient(const EnergyTerm& term, const Vector& x, double h) {
  Vector g(x.size());
  Vector xp = x;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    xp[i] = x[i] + h;
    const double ep = term.value(xp);
    xp[i] = x[i] - h;
    const double em = term.value(xp);
    xp[i] = x[i];
    g[i] = (ep - em) / (2.0 * h);
  }
  return g;
}

Vector analytic_gradient(const EnergyTerm& term, const Vector& x) {
  Vector g = Vector::Zero(x.size());
  term.add_gradient(x, g);
  return g;
}

Eigen::MatrixXd finite_difference_hessian(const EnergyTerm& term, const Vector& x, double h) {
  const Eigen::Index n = x.size();
  Eigen::MatrixXd hess(n, n);
  Vector xp = x;
  for (Eigen::Index i = 0; i < n; ++i) {
    xp[i] = x[i] + h;
    const Vector gp = analytic_gradient(term, xp);
    xp[i] = x[i] - h;
    const Vector gm = analytic_gradient(term, xp);
    xp[i] = x[i];
    hess.col(i) = (gp - gm) / (2.0 * h);
  }
  return hess;
}

Eigen::MatrixXd assembled_hessian(const EnergyTerm& term, const Vector& x, bool project_psd) {
  const std::size_t m = term.hessian_entry_count();
  std::vector<int> rows(m), cols(m);
  std::vector<double> values(m);
  term.hessian_pattern(rows.data(), cols.data());
  term.hessian_values(x, project_psd, values.data());
  Eigen::MatrixXd hess = Eigen::MatrixXd::Zero(x.size(), x.size());
  for (std::size_t k = 0; k < m; ++k) hess(rows[k], cols[k]) += values[k];
  std::vector<Eigen::Triplet<double>> triplets;  // terms whose pattern changes (contact)
  term.append_hessian_triplets(x, project_psd, triplets);
  for (const auto& t : triplets) hess(t.row(), t.col()) += t.value();
  return hess;
}

double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double floor) {
  const double scale = std::max(b.cwiseAbs().maxCoeff(), floor);
  return (a - b).cwiseAbs().maxCoeff() / scale;
}

void expect_derivatives_match_finite_differences(const EnergyTerm& term, const Vector& x,
                                                 double step, double tolerance, double floor,
                                                 double symmetry) {
  ASSERT_TRUE(std::isfinite(term.value(x)));
  const Vector g = analytic_gradient(term, x);
  EXPECT_TRUE(g.allFinite());
  EXPECT_LT(relative_error(g, finite_difference_gradient(term, x, step), floor), tolerance)
      << "gradient";
  const Eigen::MatrixXd h = assembled_hessian(term, x, false);
  ASSERT_TRUE(h.allFinite());
  EXPECT_LT(relative_error(h, finite_difference_hessian(term, x, step), floor), tolerance)
      << "Hessian";
  EXPECT_LE((h - h.transpose()).cwiseAbs().maxCoeff(), symmetry * h.cwiseAbs().maxCoeff());
}

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

Mat3 random_rotation(unsigned seed) {
  std::mt19937 rng(seed);
  return random_rotation(rng);
}

std::vector<ShellMaterial> varied_materials(int num_faces, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ShellMaterial> materials(num_faces);
  for (ShellMaterial& m : materials) {
    m.youngs_modulus = 1e6 * (0.5 + unit(rng));
    m.poisson_ratio = 0.45 * unit(rng);
    m.thickness = 1e-3 * (0.5 + unit(rng));
  }
  return materials;
}

Vector perturbed(const Positions& p, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-amplitude, amplitude);
  Vector x = as_dofs(p);
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += noise(rng);
  return x;
}

Vector rigidly_moved(const Vector& x, const Mat3& r, const Vec3& t) {
  Vector y(x.size());
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) y.segment<3>(3 * v) = r * x.segment<3>(3 * v) + t;
  return y;
}

Vec2 membrane_singular_values(const Positions& rest, const Faces& faces, const Vector& x, int f) {
  Eigen::Matrix<double, 3, 2> rest_edges, edges;
  for (int k = 0; k < 2; ++k) {
    const int a = faces(f, 0), b = faces(f, k + 1);
    rest_edges.col(k) = (rest.row(b) - rest.row(a)).transpose();
    edges.col(k) = x.segment<3>(3 * b) - x.segment<3>(3 * a);
  }
  const Eigen::Matrix3d gradient =
      edges * (rest_edges.transpose() * rest_edges).inverse() * rest_edges.transpose();
  return Eigen::JacobiSVD<Eigen::Matrix3d>(gradient).singularValues().head<2>();
}

double max_membrane_stretch(const Positions& rest, const Faces& faces, const Vector& x) {
  double stretch = 0.0;
  for (int f = 0; f < faces.rows(); ++f)
    stretch = std::max(stretch, membrane_singular_values(rest, faces, x, f)[0]);
  return stretch;
}

Eigen::VectorXd eigenvalues(const Eigen::MatrixXd& h) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(h, Eigen::EigenvaluesOnly).eigenvalues();
}

}  // namespace progsim::test_support
