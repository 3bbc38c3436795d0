#pragma once
/// @file Projection of a symmetric element Hessian onto the PSD cone (projected Newton,
/// Teran et al. 2005; as used by IPC, Li et al. 2020 §4.4).
#include <Eigen/Eigenvalues>

namespace progsim {

/// Replaces the symmetric matrix h by V max(Λ, 0) Vᵀ, its nearest PSD matrix in the
/// Frobenius norm. Fixed-size, no allocation.
/// N may be Eigen::Dynamic with a compile-time bound MaxN (no heap allocation then).
template <int N, int MaxN = N>
void project_psd(Eigen::Matrix<double, N, N, 0, MaxN, MaxN>& h) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N, 0, MaxN, MaxN>> eig(h);
  Eigen::Matrix<double, N, 1, 0, MaxN, 1> lambda = eig.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return;
  lambda = lambda.cwiseMax(0.0);
  h = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace progsim
