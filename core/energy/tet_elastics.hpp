#pragma once
/// @file Hyperelastic energy of a tetrahedral solid, one linear tet per element (VPD §3.1.3;
/// IPC, Li et al. 2020, §6), with an inversion-free step bound.
#include <vector>

#include "energy/hyperelastic_density.hpp"
#include "energy/solid_material.hpp"
#include "energy/stencil_term.hpp"
#include "solve/step_filter.hpp"

namespace progsim {

/// E(x) = Σ_t V̄_t ψ_t(F_t), F_t = D_t D̄_t⁻¹ with D = [x₁−x₀, x₂−x₀, x₃−x₀] (3×3) and D̄ the
/// rest edges, ψ_t the density of the tet's material (hyperelastic_density.hpp).
///
/// Rigid-motion invariant, zero gradient at rest. The PSD projection clamps the eigenvalues of
/// ∂P/∂F (9×9) and pulls back, H_x = V̄ Bᵀ PSD(∂P/∂F) B with B = ∂vec F/∂x constant: PSD, and
/// equal to the exact Hessian wherever ∂P/∂F is PSD, at a 9×9 instead of a 12×12 eigensolve.
/// As a StepFilter it bounds every Newton step so that no tet's volume reaches zero
/// (positive_volume_step), so no accepted state has an inverted tet, whatever the model.
class TetElastics : public StencilTerm<4>, public StepFilter {
 public:
  /// @param rest rest positions (|V| × 3), m
  /// @param tets tetrahedra (|T| × 4), indices into rest, positively oriented:
  ///        (x₁−x₀)·((x₂−x₀)×(x₃−x₀)) > 0
  /// @param tet_materials one material per tet (|T|)
  /// @throws Error(invalid_argument) if tet_materials.size() ≠ |T| or a material is out of range
  ///         (E ≤ 0, ν ∉ (−1, 0.5), non-finite);
  ///         Error(invalid_mesh) for an index out of range or a rest tet of non-positive volume.
  TetElastics(const Positions& rest, const Tets& tets,
              const std::vector<SolidMaterial>& tet_materials);

  const char* name() const override { return "solid"; }

  /// Rest volume V̄ of tet t (m³).
  double rest_volume(int t) const { return elements_[t].volume; }
  /// F of tet t at the DOFs x (3|V|).
  Mat3 deformation_gradient(int t, const Vector& x) const;

  void begin_solve(const Vector& /*x*/) override {}
  /// min over tets of positive_volume_step; NaN when x + p is not finite.
  double max_step(const Vector& x, const Vector& p) override;
  bool end_iteration(const Vector& /*x*/) override { return false; }

 protected:
  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;
  void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

 private:
  /// Per-tet constants. F = Σ_a x_a β_aᵀ, β_a the rows of beta (4×3, rows sum to zero).
  struct Element {
    Eigen::Matrix<double, 4, 3> beta;
    double volume;  ///< V̄ (m³)
    LameParameters lame;
    SolidModel model;
  };

  Mat3 element_deformation_gradient(int e, const LocalVector& xe) const;
  /// h = V̄ Bᵀ d B (12×12).
  void pull_back(int e, const Mat9& d, LocalMatrix& h) const;

  std::vector<Element> elements_;
};

}  // namespace progsim
