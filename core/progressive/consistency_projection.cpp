#include "progressive/consistency_projection.hpp"

#include <cmath>

#include "common/error.hpp"

namespace progsim {

ConsistencyProjection::ConsistencyProjection(const ProlongationMatrix& intrinsic,
                                             const Eigen::VectorXd& fine_masses,
                                             Eigen::VectorXd coarse_masses)
    : coarse_masses_(std::move(coarse_masses)) {
  const Eigen::SparseMatrix<double> u = intrinsic;
  weighted_transpose_ = u.transpose() * fine_masses.asDiagonal();
  Eigen::SparseMatrix<double> normal = weighted_transpose_ * u;
  // A coarse vertex no fine vertex depends on (a zero column of U: a coarse tet vertex whose
  // tets hold no fine vertex) says nothing about the fine state: identity row, zero weight.
  for (Eigen::Index i = 0; i < normal.rows(); ++i)
    if (!(normal.coeff(i, i) > 0.0)) {
      normal.coeffRef(i, i) = 1.0;
      coarse_masses_[i] = 0.0;
    }
  normal_.compute(normal);
  if (normal_.info() != Eigen::Success)
    fail(Status::numerical_failure, "consistency projection: UᵀMU is singular");
}

double ConsistencyProjection::distance(const Vector& fine, const Vector& coarse) const {
  const Eigen::Index n_fine = weighted_transpose_.cols(), n_coarse = weighted_transpose_.rows();
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> x(fine.data(),
                                                                                      n_fine, 3);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> y(coarse.data(),
                                                                                      n_coarse, 3);
  const Eigen::MatrixXd projected = normal_.solve(weighted_transpose_ * Eigen::MatrixXd(x));
  const Eigen::VectorXd squared = (projected - Eigen::MatrixXd(y)).rowwise().squaredNorm();
  return std::sqrt(coarse_masses_.dot(squared) / coarse_masses_.sum());
}

}  // namespace progsim
