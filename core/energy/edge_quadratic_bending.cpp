#include "energy/edge_quadratic_bending.hpp"

#include "energy/psd_projection.hpp"

namespace progsim {
namespace {

/// Jᵀ Q J for J's columns ∇s_0, ∇s_1, ∇s_2.
template <int N>
Eigen::Matrix<double, N, N> form_of_gradients(const Eigen::Matrix<double, N, 1> (&ds_dx)[3],
                                              const Mat3& q) {
  Eigen::Matrix<double, N, 3> jacobian;
  for (int i = 0; i < 3; ++i) jacobian.col(i) = ds_dx[i];
  return jacobian * q * jacobian.transpose();
}

}  // namespace

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
  h.noalias() = form_of_gradients<3 * K>(ds_dx, q);
  for (int i = 0; i < 3; ++i) h += force[i] * d2s_dx2[i];
}

template <int K>
void EdgeQuadraticBending<K>::element_projected_hessian(int e, const LocalVector& xe,
                                                        LocalMatrix& h) const {
  if (gauss_newton_) {
    LocalVector ds_dx[3];
    edge_values(e, xe, ds_dx, nullptr);
    h.noalias() = form_of_gradients<3 * K>(ds_dx, faces_[e].stiffness);  // Jᵀ Q J
    return;
  }
  element_hessian(e, xe, h);
  // At s = s̄ the Hessian is Jᵀ Q J with Q PSD: nothing to clamp.
  if (edge_values(e, xe, nullptr, nullptr) != faces_[e].rest_values) project_psd(h);
}

template class EdgeQuadraticBending<6>;
template class EdgeQuadraticBending<12>;

}  // namespace progsim
