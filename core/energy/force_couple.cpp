#include "energy/force_couple.hpp"

#include <Eigen/Eigenvalues>

#include "common/error.hpp"

namespace progsim {
namespace {

/// Relative size below which an eigenvalue of I_c counts as zero, and the largest relative
/// residual ‖I_c μ − M a‖ / |M| of a moment the group can carry.
constexpr double kSingular = 1e-12;
constexpr double kResidual = 1e-9;

/// μ solving I μ = m in the least-squares sense (pseudo-inverse of the symmetric I).
Vec3 pseudo_solve(const Mat3& inertia, const Vec3& m) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia);
  const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
  Vec3 mu = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    const double lambda = eigen.eigenvalues()[k];
    if (lambda > kSingular * largest) {
      const Vec3 u = eigen.eigenvectors().col(k);
      mu += (u.dot(m) / lambda) * u;
    }
  }
  return mu;
}

}  // namespace

Positions couple_forces(const Positions& points, const Eigen::VectorXd& weights, const Vec3& axis,
                        double moment, const std::string& where) {
  Positions forces = Positions::Zero(points.rows(), 3);
  if (moment == 0.0) return forces;
  if (!axis.allFinite() || !(axis.norm() > 0.0))
    fail(Status::invalid_scene, where + ": the moment's axis must be finite and non-zero");
  const Vec3 center = (weights.transpose() * points).transpose() / weights.sum();  // c = Σwp/Σw
  Mat3 inertia = Mat3::Zero();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vec3 d = points.row(i).transpose() - center;
    inertia += weights[i] * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());  // I_c
  }
  const Vec3 target = moment * axis.normalized();  // M a
  const Vec3 mu = pseudo_solve(inertia, target);
  if (!((inertia * mu - target).norm() <= kResidual * std::abs(moment)))
    fail(Status::invalid_scene,
         where +
             ": its vertices cannot carry a moment about this axis (they lie on one line "
             "parallel to it, or are a single vertex); select vertices off that line");
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    forces.row(i) = (weights[i] * mu.cross(points.row(i).transpose() - center)).transpose();
  return forces;
}

}  // namespace progsim
