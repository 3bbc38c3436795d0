#include "energy/wind_force.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "energy/triangle_frame.hpp"

namespace progsim {
namespace {

/// F_l = ½ ρ C_L A (n·u)(|u|² n − (n·u) u)/|u|, zero for u = 0 (Keckeisen et al. 2004's lift
/// direction, across u in the plane of u and n; magnitude ½ρC_LA|u|² cos θ sin θ).
Vec3 lift_force(const AirCoefficients& air, double area, const Vec3& n, const Vec3& u) {
  const double speed = u.norm();
  if (speed == 0.0) return Vec3::Zero();
  const double un = n.dot(u);
  return (0.5 * air.density * air.lift * area * un / speed) * (speed * speed * n - un * u);
}

}  // namespace

WindForce::WindForce(const Faces& faces, int num_vertices, const AirCoefficients& air)
    : StencilTerm<3>(triangle_stencils(faces, num_vertices, "wind"), num_vertices),
      air_(air),
      start_(Vector::Zero(3 * num_vertices)),
      normals_(faces.rows(), Vec3::Zero()),
      areas_(faces.rows(), 0.0),
      lifts_(faces.rows(), Vec3::Zero()) {}

void WindForce::lag(const Vector& start, const Vector& start_velocity, double time_step,
                    const Vec3& wind) {
  start_ = start;
  time_step_ = time_step;
  wind_ = wind;
#pragma omp parallel for schedule(static) num_threads(loop_threads(num_elements()))
  for (int e = 0; e < num_elements(); ++e) {
    const LocalVector xe = gather(e, start);
    const Vec3 normal =
        (xe.segment<3>(3) - xe.segment<3>(0)).cross(xe.segment<3>(6) - xe.segment<3>(0));
    const double twice_area = normal.norm();
    areas_[e] = 0.5 * twice_area;
    normals_[e] = twice_area > 0.0 ? Vec3(normal / twice_area) : Vec3::Zero();
    const LocalVector ve = gather(e, start_velocity);
    const Vec3 u = wind - (ve.segment<3>(0) + ve.segment<3>(3) + ve.segment<3>(6)) / 3.0;
    lifts_[e] = air_.lift != 0.0 ? lift_force(air_, areas_[e], normals_[e], u) : Vec3::Zero();
  }
}

Vec3 WindForce::relative_wind(int e, const LocalVector& xe) const {
  const LocalVector se = gather(e, start_);
  const Vec3 moved = xe.segment<3>(0) + xe.segment<3>(3) + xe.segment<3>(6) - se.segment<3>(0) -
                     se.segment<3>(3) - se.segment<3>(6);
  return wind_ - moved / (3.0 * time_step_);  // u = w − v̄, v̄ = Σ(x_i − x_iᵗ)/(3h)
}

Vec3 WindForce::drag(int e, const Vec3& u) const {
  const double un = normals_[e].dot(u);  // F_d = ½ρC_dA |u_n| u_n n (drag equation on u_n)
  return (0.5 * air_.density * air_.drag * areas_[e] * std::abs(un) * un) * normals_[e];
}

double WindForce::element_value(int e, const LocalVector& xe) const {
  const Vec3 u = relative_wind(e, xe);
  const double un = std::abs(normals_[e].dot(u));
  const double psi = 0.5 * air_.density * air_.drag * areas_[e] * un * un * un / 3.0;  // ψ(u)
  const Vec3 moved = time_step_ * (wind_ - u);     // Σ(x_i − x_iᵗ)/3 = h (w − u)
  return time_step_ * psi - lifts_[e].dot(moved);  // E_f = h ψ(u) − F_l·Σ(x_i − x_iᵗ)/3
}

void WindForce::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  const Vec3 force = drag(e, relative_wind(e, xe)) + lifts_[e];
  for (int k = 0; k < 3; ++k) g.segment<3>(3 * k) = -force / 3.0;  // ∂u/∂x_i = −I/(3h)
}

void WindForce::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  const double un = std::abs(normals_[e].dot(relative_wind(e, xe)));
  // ∇²ψ = ρC_dA |u_n| n nᵀ, and ∂²E/∂x_i∂x_j = h (∂u/∂x_i)ᵀ ∇²ψ (∂u/∂x_j) = ∇²ψ/(9h).
  const Mat3 block = (air_.density * air_.drag * areas_[e] * un / (9.0 * time_step_)) *
                     normals_[e] * normals_[e].transpose();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) h.block<3, 3>(3 * i, 3 * j) = block;
}

void WindForce::element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  element_hessian(e, xe, h);
}

Vec3 WindForce::total_force(const Vector& x) const {
  Vec3 total = Vec3::Zero();
  for (int e = 0; e < num_elements(); ++e)
    total += drag(e, relative_wind(e, gather(e, x))) + lifts_[e];
  return total;
}

}  // namespace progsim
