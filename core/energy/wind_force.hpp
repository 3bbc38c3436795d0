#pragma once
/// @file Aerodynamic drag and lift of a wind on a shell's faces, as a term of the implicit-Euler
/// incremental potential.
#include <vector>

#include "energy/stencil_term.hpp"

namespace progsim {

/// The air and the faces' response to it.
struct AirCoefficients {
  double density = 1.2;  ///< ρ (kg/m³)
  double drag = 1.2;     ///< C_d of the pressure drag normal to a face (1)
  double lift = 0.0;     ///< C_L of the lift across the relative wind (1); 0: no lift
};

/// The wind's force on a shell, per face f with relative wind u_f = w − v̄_f (w the wind, v̄_f the
/// mean velocity of the face's vertices), unit normal n_f and area A_f, each vertex taking a third:
///
/// - drag, normal to the face: F_d = ½ ρ C_d A |u_n| u_n n, u_n = n·u (the drag equation on the
///   face's normal flow; ARCSim's wind_force, Narain et al. 2012, physics.cpp, is this with
///   ½C_d = 1). Implicit: with v̄_f = Σ_{i∈f}(x_i − x_iᵗ)/(3h) it is −∇E of the convex dissipation
///   potential E_f(x) = h ψ(u_f(x)), ψ(u) = ⅓ · ½ρC_dA |n·u|³, so the solve evaluates it at the
///   step's end velocity like the inertia; its Hessian (ρC_dA/(9h)) |u_n| n nᵀ per vertex pair is
///   exact and positive semi-definite.
/// - lift, across u in the plane of u and n (direction as Keckeisen et al. 2004 model it):
///   F_l = ½ ρ C_L A (n·u)(|u|² n − (n·u) u)/|u|, of magnitude ½ρC_LA|u|² cos θ sin θ (θ between
///   n and u; the flat plate's sin α cos α, zero across and along the flow). Not a gradient:
///   explicit, from the velocities at the step's start, as the linear energy −F_l·Σ(x_i − x_iᵗ)/3.
///
/// Normals and areas are lagged at the step's start xᵗ (like IPC's lagged friction, Li et al.
/// 2020 §5): set them, h and w with lag() before each solve.
class WindForce : public StencilTerm<3> {
 public:
  /// @param faces the shell's triangles (|F| × 3); throws Error(invalid_mesh) on a bad index
  /// @param num_vertices |V|
  /// @param air ρ, C_d, C_L
  WindForce(const Faces& faces, int num_vertices, const AirCoefficients& air);

  const char* name() const override { return "wind"; }

  /// Freezes the step: start positions xᵗ and velocities vᵗ (3|V|, m and m/s), time step h (s)
  /// and wind w (m/s, at the step's end time). Normals, areas and lift forces come from them.
  void lag(const Vector& start, const Vector& start_velocity, double time_step, const Vec3& wind);

  /// The wind w the term was lagged with (m/s).
  const Vec3& wind() const { return wind_; }
  /// Σ_f (F_d + F_l) at x (N): the force on the whole shell with v = (x − xᵗ)/h.
  Vec3 total_force(const Vector& x) const;

 protected:
  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;
  /// The exact Hessian: it is already positive semi-definite.
  void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

 private:
  /// u_f = w − Σ_{i∈f}(x_i − x_iᵗ)/(3h) at the face's stacked positions xe.
  Vec3 relative_wind(int e, const LocalVector& xe) const;
  /// F_d of face e at relative wind u (N).
  Vec3 drag(int e, const Vec3& u) const;

  AirCoefficients air_;
  Vector start_;  ///< xᵗ (3|V|)
  double time_step_ = 1.0;
  Vec3 wind_ = Vec3::Zero();
  std::vector<Vec3> normals_;  ///< unit normal of each face at xᵗ
  std::vector<double> areas_;  ///< area of each face at xᵗ (m²)
  std::vector<Vec3> lifts_;    ///< F_l of each face from the velocities at the step's start (N)
};

}  // namespace progsim
