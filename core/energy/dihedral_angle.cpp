#include "energy/dihedral_angle.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace progsim {
namespace {

/// [v]×, the matrix of v × · (3×3).
Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace

double dihedral_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Vec3 e = x1 - x0;
  const Vec3 n1 = e.cross(x2 - x0), n2 = (x3 - x0).cross(e);
  const double length = e.norm();
  // θ = atan2((n₁ × n₂)·ê, n₁·n₂): both arguments carry the same factor ‖n₁‖‖n₂‖ > 0.
  return std::atan2(length > 0.0 ? n1.cross(n2).dot(e) / length : 0.0, n1.dot(n2));
}

HingeFrame::HingeFrame(const Vector12& xe) {
  const Vec3 x0 = xe.segment<3>(0);
  e = xe.segment<3>(3) - x0;
  w = xe.segment<3>(6) - x0;
  u = xe.segment<3>(9) - x0;
  n1 = e.cross(w);
  n2 = u.cross(e);
  const double e_sq = e.squaredNorm();
  length = std::sqrt(e_sq);
  n1_sq = n1.squaredNorm();
  n2_sq = n2.squaredNorm();
  t1 = w.dot(e) / e_sq;
  t2 = u.dot(e) / e_sq;
  m1 = (length / n1_sq) * n1;
  m2 = (length / n2_sq) * n2;
}

double HingeFrame::angle() const {
  // As dihedral_angle(): atan2((n₁ × n₂)·ê, n₁·n₂).
  return std::atan2(length > 0.0 ? n1.cross(n2).dot(e) / length : 0.0, n1.dot(n2));
}

Vector12 HingeFrame::angle_gradient() const {
  Vector12 g;
  g.segment<3>(0) = (1.0 - t1) * m1 + (1.0 - t2) * m2;
  g.segment<3>(3) = t1 * m1 + t2 * m2;
  g.segment<3>(6) = -m1;
  g.segment<3>(9) = -m2;
  return g;
}

Matrix12 HingeFrame::angle_hessian() const {
  const double e_sq = length * length;
  const Vec3 e_hat = e / length;
  // ∂m_i/∂x_j = n_i/‖n_i‖² (∂‖e‖/∂x_j)ᵀ + ‖e‖/‖n_i‖² (I − 2 n̂_i n̂_iᵀ) ∂n_i/∂x_j.
  const Mat3 p1 = (length / n1_sq) * (Mat3::Identity() - (2.0 / n1_sq) * n1 * n1.transpose());
  const Mat3 p2 = (length / n2_sq) * (Mat3::Identity() - (2.0 / n2_sq) * n2 * n2.transpose());
  const Vec3 a1 = n1 / n1_sq, a2 = n2 / n2_sq;
  Mat3 dm1[4], dm2[4];                                          // ∂m₁/∂x_j, ∂m₂/∂x_j
  dm1[0] = -a1 * e_hat.transpose() + p1 * cross_matrix(w - e);  // ∂n₁/∂x0 = [w − e]×
  dm1[1] = a1 * e_hat.transpose() - p1 * cross_matrix(w);       // ∂n₁/∂x1 = −[w]×
  dm1[2] = p1 * cross_matrix(e);                                // ∂n₁/∂x2 = [e]×
  dm1[3].setZero();
  dm2[0] = -a2 * e_hat.transpose() + p2 * cross_matrix(e - u);  // ∂n₂/∂x0 = [e − u]×
  dm2[1] = a2 * e_hat.transpose() + p2 * cross_matrix(u);       // ∂n₂/∂x1 = [u]×
  dm2[2].setZero();
  dm2[3] = -p2 * cross_matrix(e);  // ∂n₂/∂x3 = −[e]×
  // ∂t_i/∂x_j, from t₁ = (w·e)/‖e‖², t₂ = (u·e)/‖e‖².
  Vec3 dt1[4], dt2[4];
  dt1[1] = (w - 2.0 * t1 * e) / e_sq;
  dt1[2] = e / e_sq;
  dt1[3].setZero();
  dt1[0] = -dt1[1] - dt1[2];
  dt2[1] = (u - 2.0 * t2 * e) / e_sq;
  dt2[2].setZero();
  dt2[3] = e / e_sq;
  dt2[0] = -dt2[1] - dt2[3];
  Matrix12 h;
  for (int j = 0; j < 4; ++j) {
    const Mat3 c1 = m1 * dt1[j].transpose(), c2 = m2 * dt2[j].transpose();
    h.block<3, 3>(0, 3 * j) = (1.0 - t1) * dm1[j] - c1 + (1.0 - t2) * dm2[j] - c2;
    h.block<3, 3>(3, 3 * j) = t1 * dm1[j] + c1 + t2 * dm2[j] + c2;
    h.block<3, 3>(6, 3 * j) = -dm1[j];
    h.block<3, 3>(9, 3 * j) = -dm2[j];
  }
  return 0.5 * (h + h.transpose());  // exact up to rounding; make it symmetric bit for bit
}

}  // namespace progsim
