#pragma once
/// @file Test helpers that check an EnergyTerm against finite differences, independently of
/// the term's own derivative code.
#include <Eigen/Sparse>
#include <random>
#include <vector>

#include "energy/energy_term.hpp"
#include "energy/shell_material.hpp"

namespace progsim::test_support {

/// ∇E by central differences of value() (step h per DOF).
Vector finite_difference_gradient(const EnergyTerm& term, const Vector& x, double h);

/// ∇²E by central differences of add_gradient() (step h per DOF), dense (3|V| × 3|V|).
Eigen::MatrixXd finite_difference_hessian(const EnergyTerm& term, const Vector& x, double h);

/// The term's analytic gradient (3|V|).
Vector analytic_gradient(const EnergyTerm& term, const Vector& x);

/// The term's Hessian assembled from its triplets, dense (3|V| × 3|V|).
Eigen::MatrixXd assembled_hessian(const EnergyTerm& term, const Vector& x, bool project_psd);

/// Max |a − b| / max(‖b‖∞, floor): relative error with an absolute floor.
double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double floor);

/// Expects the term's value, gradient and assembled (unprojected) Hessian at x to be finite,
/// the gradient and Hessian to match central finite differences of step `step` (relative_error
/// with `floor` below `tolerance`), and the Hessian to be symmetric to `symmetry` times its
/// largest entry (0: exactly).
void expect_derivatives_match_finite_differences(const EnergyTerm& term, const Vector& x,
                                                 double step, double tolerance,
                                                 double floor = 1e-12, double symmetry = 1e-12);

/// A random rotation matrix (uniform on SO(3): a normalized Gaussian quaternion) drawn from rng.
Mat3 random_rotation(std::mt19937& rng);

/// random_rotation drawn from a generator seeded with `seed`.
Mat3 random_rotation(unsigned seed);

/// Materials that differ from face to face (E, ν, t drawn from a seed), so a mix-up of
/// per-face data shows.
std::vector<ShellMaterial> varied_materials(int num_faces, unsigned seed);

/// The DOFs of p plus uniform noise in [−amplitude, amplitude] per coordinate.
Vector perturbed(const Positions& p, double amplitude, unsigned seed);

/// Rx + t applied to every vertex of x (3|V|).
Vector rigidly_moved(const Vector& x, const Mat3& r, const Vec3& t);

/// Singular values (σ₁ ≥ σ₂) of face f's membrane deformation gradient at x (3|V|): Eigen's SVD
/// of F = D (D̄ᵀD̄)⁻¹ D̄ᵀ (D̄, D the rest and deformed edges of the face), written independently of
/// the energy terms' closed-form spectrum.
Vec2 membrane_singular_values(const Positions& rest, const Faces& faces, const Vector& x, int f);

/// The largest σ₁ over all faces (membrane_singular_values).
double max_membrane_stretch(const Positions& rest, const Faces& faces, const Vector& x);

/// Eigenvalues of a symmetric matrix, ascending.
Eigen::VectorXd eigenvalues(const Eigen::MatrixXd& h);

}  // namespace progsim::test_support
