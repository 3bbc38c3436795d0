#pragma once
/// @file The tension-field (relaxed) neo-Hookean membrane: the energy a membrane keeps when it
/// may wrinkle below the mesh's resolution (Pipkin 1986, "The relaxed energy density for
/// isotropic elastic membranes"; Steigmann 1990; Skouras et al. 2014 §4).
#include "energy/neo_hookean_membrane.hpp"
#include "energy/stretch_spectrum.hpp"

namespace progsim {

/// Neo-Hookean membrane whose compression costs nothing: with σ₁ ≥ σ₂ the singular values of
/// the face's deformation gradient F and Ψ(σ₁, σ₂) the energy density of NeoHookeanMembrane,
///   W = 0                 if σ₁ ≤ 1                           (slack: compressed both ways),
///   W = Ψ(σ₁, σ₂*(σ₁))    if σ₁ > 1 and ∂Ψ/∂σ₂(σ₁, σ₂) < 0    (wrinkled: tension along u₁ only),
///   W = Ψ(σ₁, σ₂)         otherwise                           (taut),
/// where σ₂*(σ₁) is the transverse stretch of uniaxial tension, ∂Ψ/∂σ₂(σ₁, σ₂*) = 0. This is
/// the relaxed energy W(C) = min over C' ≥ C of Ψ (Pipkin 1986): wrinkles too fine for the
/// mesh can shorten a face's lengths at no cost but cannot lengthen them. W is C¹; its Hessian
/// jumps between the three states. A coarse preview uses it so that a cloth draping over an
/// obstacle is not held up by the compression its coarse faces cannot fold away (membrane
/// locking); the finest level keeps NeoHookeanMembrane.
///
/// A share ε of the full energy stays in the wrinkled and slack states, W_ε = (1 − ε) W + ε Ψ
/// (taut faces: Ψ exactly), so that compression is cheap but a face cannot collapse to a
/// segment (Ψ's +∞ there): without it a tightly wrung cloth's preview crumples its faces flat
/// and refinement finds no safe place for the new vertices (the twist at 289 vertices). The
/// wrinkled Hessian is built from the closed-form eigensystem of ∂²σ₁/∂F² (Smith et al. 2019);
/// the projected Hessian sums the two parts' exact projections.
class TensionFieldMembrane : public NeoHookeanMembrane {
 public:
  /// Default share of the full energy in compression.
  static constexpr double kDefaultCompressionShare = 1e-3;

  /// As NeoHookeanMembrane, with ε = compression_share in [0, 1).
  /// @throws Error(invalid_argument) if compression_share is outside [0, 1).
  TensionFieldMembrane(const Positions& rest, const Faces& faces,
                       const std::vector<ShellMaterial>& face_materials,
                       double compression_share = kDefaultCompressionShare);

  const char* name() const override { return "tension_field_membrane"; }

 protected:
  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;
  void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

 private:
  /// ∂²W/∂F² (6×6) of a wrinkled face with principal stretches s, its eigenvalues clamped at 0
  /// when `project`.
  Matrix6 wrinkled_stress_derivative(int e, const Mat32& f, const StretchSpectrum& s,
                                     bool project) const;
  /// ∇²E_e of W_ε (9×9), each part's Hessian projected to PSD when `project`.
  void blended_hessian(int e, const LocalVector& xe, bool project, LocalMatrix& h) const;
  /// d ← ε d: the full energy's share of a gradient or Hessian.
  template <typename Derivative>
  void scale_full_part(Derivative& d) const;

  double share_;  ///< ε
};

}  // namespace progsim
