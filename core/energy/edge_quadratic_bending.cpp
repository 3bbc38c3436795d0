#include "energy/edge_quadratic_bending.hpp"

#include "energy/psd_projection.hpp"

namespace progsim {

template <int K>
double EdgeQuadraticBending<K>::element_value(int e, const LocalVector& xe) const {
  const Vec3 ds = edge_values(e, xe, nullptr, nullptr) - faces_[e].rest_values;
  return 0.5 * ds.dot(faces_[e].stiffness * ds);  // ½ Δsᵀ Q Δs
}

template <int K>
void EdgeQuadraticBending<K>::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  LocalVector ds_dx[3];
  const Vec3 ds = edge_values(e, xe, ds_dx, nullptr) - faces_[e].rest_values;
  const Vec3 force = faces_[e].stiffness * ds;  // ∂E/∂s = Q Δs
  g = force[0] * ds_dx[0] + force[1] * ds_dx[1] + force[2] * ds_dx[2];
}

template <int K>
void EdgeQuadraticBending<K>::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  LocalVector ds_dx[3];
  LocalMatrix d2s_dx2[3];
  const Vec3 ds = edge_values(e, xe, ds_dx, d2s_dx2) - faces_[e].rest_values;
  const Mat3& q = faces_[e].stiffness;
  const Vec3 force = q * ds;
  // ∇²E = Σ_ij Q_ij ∇s_i ∇s_jᵀ + Σ_i (Q Δs)_i ∇²s_i.
  Eigen::Matrix<double, 3 * K, 3> jacobian;
  for (int i = 0; i < 3; ++i) jacobian.col(i) = ds_dx[i];
  h.noalias() = jacobian * q * jacobian.transpose();
  for (int i = 0; i < 3; ++i) h += force[i] * d2s_dx2[i];
}

template <int K>
void EdgeQuadraticBending<K>::element_projected_hessian(int e, const LocalVector& xe,
                                                        LocalMatrix& h) const {
  element_hessian(e, xe, h);
  // At s = s̄ the Hessian is Jᵀ Q J with Q PSD: nothing to clamp.
  if (edge_values(e, xe, nullptr, nullptr) != faces_[e].rest_values) project_psd(h);
}

template class EdgeQuadraticBending<6>;
template class EdgeQuadraticBending<12>;

}  // namespace progsim
