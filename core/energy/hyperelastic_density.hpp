#pragma once
/// @file The energy density ψ(F) of an isotropic hyperelastic solid, its first Piola–Kirchhoff
/// stress P = ∂ψ/∂F and the stress derivative ∂P/∂F, for a 3×3 deformation gradient F.
#include "common/types.hpp"
#include "energy/solid_material.hpp"

namespace progsim {

/// ∂P/∂F as a 9×9 matrix over vec F, column-major (row/column i + 3j is F_ij).
using Mat9 = Eigen::Matrix<double, 9, 9>;

/// ψ(F), J/m³. +∞ where the model is undefined (neo-Hookean with det F ≤ 0).
double hyperelastic_density(SolidModel model, const LameParameters& lame, const Mat3& f);

/// P(F) = ∂ψ/∂F, Pa. Quiet NaN where ψ is infinite.
Mat3 first_piola_stress(SolidModel model, const LameParameters& lame, const Mat3& f);

/// ∂P/∂F = ∂²ψ/∂F² (exact, symmetric, not projected), Pa. Quiet NaN where ψ is infinite.
Mat9 stress_derivative(SolidModel model, const LameParameters& lame, const Mat3& f);

}  // namespace progsim
