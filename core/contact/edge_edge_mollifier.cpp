#include "contact/edge_edge_mollifier.hpp"

#include <Eigen/Geometry>

namespace progsim {
namespace {

/// Edge vector ea = ea1 − ea0 of the stencil x.
Vec3 edge_a(const Vec12& x) {
  return x.segment<3>(3) - x.segment<3>(0);
}

/// Edge vector eb = eb1 − eb0 of the stencil x.
Vec3 edge_b(const Vec12& x) {
  return x.segment<3>(9) - x.segment<3>(6);
}

/// m as a function of c = ‖ea × eb‖² (IPC eq. 23).
double mollifier_of(double c, double eps_x) {
  if (c >= eps_x) return 1.0;
  const double r = c / eps_x;
  return (2.0 - r) * r;  // −c²/ε_x² + 2c/ε_x
}

/// m'(c) = 2(1 − c/ε_x)/ε_x for c < ε_x (IPC eq. 23).
double mollifier_slope(double c, double eps_x) {
  return 2.0 * (1.0 - c / eps_x) / eps_x;
}

/// Chain rule through ea = x1 − x0 (component 0 of (ea, eb)), eb = x3 − x2 (component 1).
constexpr int kComponent[4] = {0, 0, 1, 1};
constexpr double kSign[4] = {-1.0, 1.0, -1.0, 1.0};

}  // namespace

double mollifier_threshold(const Vec12& rest_x) {
  // ε_x = 10⁻³ ‖ēa‖²‖ēb‖² (IPC §4.3)
  return 1e-3 * edge_a(rest_x).squaredNorm() * edge_b(rest_x).squaredNorm();
}

double mollifier(const Vec12& x, double eps_x) {
  return mollifier_of(edge_a(x).cross(edge_b(x)).squaredNorm(), eps_x);
}

double mollifier_gradient(const Vec12& x, double eps_x, Vec12& grad) {
  const Vec3 ea = edge_a(x), eb = edge_b(x);
  const double c = ea.cross(eb).squaredNorm();
  grad.setZero();
  if (c >= eps_x) return 1.0;
  const Vec6 gc = mollifier_slope(c, eps_x) * cross_squared_norm_gradient(ea, eb);  // ∇m = m'∇c
  for (int i = 0; i < 4; ++i) grad.segment<3>(3 * i) = kSign[i] * gc.segment<3>(3 * kComponent[i]);
  return mollifier_of(c, eps_x);
}

void mollifier_derivatives(const Vec12& x, double eps_x, double& m, Vec12& grad, Mat12& hess) {
  Vec6 gc;
  Mat6 hc;
  const double c = cross_squared_norm_derivatives(edge_a(x), edge_b(x), gc, hc);
  m = mollifier_of(c, eps_x);
  grad.setZero();
  hess.setZero();
  if (c >= eps_x) return;
  // ∇m = m'∇c, ∇²m = m''∇c∇cᵀ + m'∇²c, m''(c) = −2/ε_x².
  const double dm = mollifier_slope(c, eps_x), ddm = -2.0 / (eps_x * eps_x);
  const Mat6 h6 = ddm * gc * gc.transpose() + dm * hc;
  for (int i = 0; i < 4; ++i) {
    grad.segment<3>(3 * i) = kSign[i] * dm * gc.segment<3>(3 * kComponent[i]);
    for (int j = 0; j < 4; ++j) {
      hess.block<3, 3>(3 * i, 3 * j) =
          kSign[i] * kSign[j] * h6.block<3, 3>(3 * kComponent[i], 3 * kComponent[j]);
    }
  }
}

}  // namespace progsim
