#include "contact/friction_potential.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "common/error.hpp"
#include "common/parallel.hpp"

namespace progsim {
namespace {

/// An orthonormal basis (3 × 2) of the plane orthogonal to the unit vector n.
Eigen::Matrix<double, 3, 2> tangent_basis(const Vec3& n) {
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 t0 = n.cross(helper).normalized();
  Eigen::Matrix<double, 3, 2> basis;
  basis << t0, n.cross(t0);
  return basis;
}

}  // namespace

double friction_smoothing(double y, double epsilon) {
  if (y >= epsilon) return y;
  return -y * y * y / (3.0 * epsilon * epsilon) + y * y / epsilon + epsilon / 3.0;
}

double friction_smoothing_slope_over_y(double y, double epsilon) {
  return y >= epsilon ? 1.0 / y : 2.0 / epsilon - y / (epsilon * epsilon);
}

FrictionPotential::FrictionPotential(const ContactPotential& contact, double slip_threshold)
    : contact_(contact), epsilon_(slip_threshold) {
  if (!(slip_threshold > 0.0) || !std::isfinite(slip_threshold))
    fail(Status::invalid_argument,
         "friction: slip threshold = " + std::to_string(slip_threshold) + " must be > 0");
}

void FrictionPotential::lag(const Vector& x0) {
  x0_ = x0;
  obstacles0_ = contact_.obstacle_positions();
  contacts_.clear();
  for (const ContactPoint& p : contact_.contact_points(x0))
    contacts_.push_back({p, tangent_basis(p.normal)});
}

Vec3 FrictionPotential::displacement(int v, const Vector& x) const {
  const int n = contact_.mesh().num_shell_vertices;
  if (v < n) return x.segment<3>(3 * v) - x0_.segment<3>(3 * v);
  return (contact_.obstacle_positions().row(v - n) - obstacles0_.row(v - n)).transpose();
}

Vec2 FrictionPotential::slip(const Contact& c, const Vector& x) const {
  Vec3 relative = Vec3::Zero();  // Σ_j w_j Δx_j: relative motion of the closest points
  for (int j = 0; j < 4; ++j)
    if (c.point.vertices[j] >= 0)
      relative += c.point.weights[j] * displacement(c.point.vertices[j], x);
  return c.basis.transpose() * relative;
}

double FrictionPotential::value(const Vector& x) const {
  const int n = num_contacts();
  return ordered_sum(n, [&](long k) {
    const Contact& c = contacts_[k];
    return c.point.friction * c.point.normal_force *
           friction_smoothing(slip(c, x).norm(), epsilon_);  // IPC eq. 14
  });
}

void FrictionPotential::add_gradient(const Vector& x, Vector& g) const {
  const int num_shell = contact_.mesh().num_shell_vertices;
  for (const Contact& c : contacts_) {
    const Vec2 u = slip(c, x);
    // ∇_j D_k = μλ (f1(y)/y) w_j P u (IPC eq. 16)
    const Vec3 force = c.point.friction * c.point.normal_force *
                       friction_smoothing_slope_over_y(u.norm(), epsilon_) * (c.basis * u);
    for (int j = 0; j < 4; ++j) {
      const int v = c.point.vertices[j];
      if (v >= 0 && v < num_shell) g.segment<3>(3 * v) += c.point.weights[j] * force;
    }
  }
}

void FrictionPotential::append_hessian_triplets(const Vector& x, bool /*project_psd*/,
                                                std::vector<Eigen::Triplet<double>>& out) const {
  const int num_shell = contact_.mesh().num_shell_vertices;
  for (const Contact& c : contacts_) {
    const Vec2 u = slip(c, x);
    const double y = u.norm();
    // M = (f1/y) I + ((f1'y − f1)/y³) uuᵀ, PSD for every y (IPC §5.2); f1'y − f1 = −y²/ε² below ε
    Mat2 m = friction_smoothing_slope_over_y(y, epsilon_) * Mat2::Identity();
    if (y >= epsilon_)
      m -= u * u.transpose() / (y * y * y);
    else if (y > 0.0)
      m -= u * u.transpose() / (epsilon_ * epsilon_ * y);
    const Mat3 block = c.point.friction * c.point.normal_force * c.basis * m * c.basis.transpose();
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int va = c.point.vertices[a], vb = c.point.vertices[b];
        if (va < 0 || vb < 0 || va >= num_shell || vb >= num_shell) continue;
        const double w = c.point.weights[a] * c.point.weights[b];
        if (w == 0.0) continue;
        for (int col = 0; col < 3; ++col)
          for (int row = 0; row < 3; ++row)
            out.emplace_back(3 * va + row, 3 * vb + col, w * block(row, col));
      }
  }
}

}  // namespace progsim
