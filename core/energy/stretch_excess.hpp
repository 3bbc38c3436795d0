#pragma once
/// @file A quadratic penalty on membrane principal stretches beyond a target: the objective of
/// the strain-limit correction of a refined start (PSQ, Zhang et al. 2023, §4.4.5).
#include <vector>

#include "energy/stencil_term.hpp"
#include "energy/triangle_frame.hpp"

namespace progsim {

/// E(x) = ρ Σ_f Ā_f Σ_{i=1,2} (σ_i,f − t_f)₊²
/// with σ₁ ≥ σ₂ the singular values of face f's membrane deformation gradient F = D D̄⁻¹ (as in
/// StrainLimit), t_f > 0 the face's target stretch, Ā_f its rest area and ρ the stiffness
/// (energy per rest area). Finite everywhere, C¹ (the Hessian jumps where σ_i crosses t_f).
///
/// h(σ) = (σ − t)₊² is convex and non-decreasing on σ ≥ 0, so E is a convex function of F
/// (Lewis 1995), hence of x: the exact Hessian is PSD and is its own projection. Derivatives as a
/// spectral function of C = FᵀF (energy/spectral_stretch.hpp), smooth at σ₁ = σ₂.
class StretchExcess : public StencilTerm<3> {
 public:
  /// @param rest rest positions (|V| × 3), m
  /// @param faces triangles (|F| × 3)
  /// @param targets t_f > 0 per face (|F|)
  /// @param stiffness ρ > 0
  /// @throws Error(invalid_argument) for a wrong number of targets, a target or stiffness that
  ///         is not > 0 and finite; Error(invalid_mesh) for an index out of range or a
  ///         degenerate rest triangle.
  StretchExcess(const Positions& rest, const Faces& faces, std::vector<double> targets,
                double stiffness);

  const char* name() const override { return "stretch_excess"; }
  double stiffness() const { return stiffness_; }
  /// Sets ρ. @throws Error(invalid_argument) unless > 0 and finite.
  void set_stiffness(double stiffness);

 protected:
  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;
  /// The exact Hessian, which is PSD (see the class comment).
  void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

 private:
  struct Element {
    Mat32 beta;     ///< ∂F/∂x_a = I₃ ⊗ β_aᵀ
    double area;    ///< Ā (m²)
    double target;  ///< t_f
  };
  std::vector<Element> elements_;
  double stiffness_;
};

}  // namespace progsim
