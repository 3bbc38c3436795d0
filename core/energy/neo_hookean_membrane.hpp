#pragma once
/// @file Neo-Hookean membrane energy of a thin shell, one triangle per element (DESIGN.md §2;
/// PSQ footnote 1; Chen et al. 2018; C-IPC, Li et al. 2021 §4).
#include <vector>

#include "energy/shell_material.hpp"
#include "energy/stencil_term.hpp"
#include "energy/triangle_frame.hpp"

namespace progsim {

/// Membrane (stretching and shearing) energy of a triangle mesh:
///   E(x) = Σ_f t_f Ā_f W(C_f),  W = μ/2 (tr C − 2 − ln det C) + λ/8 (ln det C)²,
/// with C = ā⁻¹a the ratio of the current first fundamental form a (2×2, from the edge vectors)
/// to the rest one ā, μ the shear modulus and λ the plane-stress Lamé parameter of each face.
/// Evaluated through the deformation gradient F = D D̄⁻¹ (3×2), where D = [x1−x0, x2−x0]
/// (3×2) and D̄ the rest edges in a 2D frame of the rest triangle, so that C ~ FᵀF.
///
/// The energy is rigid-motion invariant and has zero gradient at the rest shape, flat or
/// curved. A degenerate current triangle (zero area, det C = 0) has infinite energy: value()
/// returns +∞ (so a line search rejects the step) and the gradient and Hessian blocks of that
/// element are quiet NaN (so a solver that checks finiteness stops instead of using garbage).
/// The PSD projection is done exactly in F-space (6×6): H_x = t Ā Bᵀ PSD(∂²W/∂F²) B with
/// B = ∂vec F/∂x constant, which is PSD and equals the exact Hessian whenever that one is PSD.
/// PSD(·) is the eigenvalue clamp, computed from the closed-form eigensystem of the isotropic
/// energy (no numerical eigen-decomposition).
class NeoHookeanMembrane : public StencilTerm<3> {
 public:
  /// @param rest rest positions (|V| × 3), m
  /// @param faces triangles (|F| × 3), indices into rest
  /// @param face_materials one material per face (|F|): E (Pa), ν, thickness t (m)
  /// @throws Error(invalid_argument) if face_materials.size() ≠ |F|;
  ///         Error(invalid_mesh) if a rest triangle has zero (or non-finite) area.
  NeoHookeanMembrane(const Positions& rest, const Faces& faces,
                     const std::vector<ShellMaterial>& face_materials);

  const char* name() const override { return "membrane"; }

  /// Rest area Ā of face f (m²).
  double rest_area(int f) const { return rest_area_[f]; }

 protected:
  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;
  void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

 protected:
  /// Per-face constants. F = Σ_a x_a β_aᵀ (3×2), β_a the rows of `beta` (3×2).
  struct Element {
    Eigen::Matrix<double, 3, 2> beta;  ///< ∂F/∂x_a = I₃ ⊗ β_aᵀ; rows sum to zero
    double weight;                     ///< t Ā (m³)
    double mu;                         ///< μ (Pa)
    double lambda;                     ///< plane-stress λ (Pa)
  };
  using Matrix6 = Eigen::Matrix<double, 6, 6>;

  /// ∂²W/∂F² (6×6, vec F column-major) at F; false if det C ≤ 0.
  bool stress_derivative(int e, const Eigen::Matrix<double, 3, 2>& f, Matrix6& hf) const;
  /// PSD projection of ∂²W/∂F² from its closed-form eigensystem; false if det C ≤ 0.
  bool projected_stress_derivative(int e, const Eigen::Matrix<double, 3, 2>& f, Matrix6& hf) const;
  /// h = t Ā Bᵀ hf B (9×9).
  void pull_back(int e, const Matrix6& hf, LocalMatrix& h) const;

  std::vector<Element> elements_;

 private:
  std::vector<double> rest_area_;
};

}  // namespace progsim
