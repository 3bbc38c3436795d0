#pragma once
/// @file Strain-limiting barrier on the membrane singular values of a triangle mesh (C-IPC,
/// Li et al. 2021, §5 "strain limiting").
#include <vector>

#include "energy/stencil_term.hpp"
#include "energy/triangle_frame.hpp"

namespace progsim {

/// Strain-limiting barrier of a triangle mesh (C-IPC, Li, Kaufman & Jiang 2021, §5):
///   E(x) = Σ_f Ā_f κ c_f Σ_{i=1,2} b(s_f − σ_i,f, ŝ),
///   b(d, d̂) = −(d − d̂)² ln(d/d̂) for 0 < d < d̂,  0 for d ≥ d̂,  +∞ for d ≤ 0,
/// where σ₁ ≥ σ₂ are the singular values of the membrane deformation gradient F = D D̄⁻¹ (3×2)
/// of face f (D = [x1−x0, x2−x0], D̄ the rest edges in a 2D frame of the rest triangle, as in
/// NeoHookeanMembrane), s_f > 1 the face's strain limit, ŝ the activation band (the barrier acts
/// once σ > s_f − ŝ), κ the stiffness (Pa·m, energy per rest area) and c_f ≥ 1 the face's
/// barrier scale (1 unless fit_limits stiffened a held face, see there).
///
/// Values: a face with σ₁ ≥ s_f has infinite energy, so value() is +∞ (a line search rejects
/// the step); the gradient and Hessian blocks of such a face are quiet NaN (as for a degenerate
/// triangle in NeoHookeanMembrane). Faces with σ₁ ≤ s_f − ŝ contribute exactly zero value,
/// gradient and Hessian (early out). b is C² at d = d̂, so E is C² everywhere it is finite.
///
/// Derivatives: Σ_i b(s − σ_i) = Σ_i g(λ_i) is a spectral function of C = FᵀF (λ_i = σ_i²),
/// smooth also at σ₁ = σ₂. ∂/∂C = V diag(g'(λ_i)) Vᵀ (Lewis 1996, "Derivatives of spectral
/// functions"); the second derivative is the divided-difference (Daleckii–Krein) form
/// (Lewis & Sendov 2001, "Twice differentiable spectral functions"), with the divided
/// difference [g'(λ₁) − g'(λ₂)]/(λ₁ − λ₂) replaced by the mean of g''(λ₁), g''(λ₂) when
/// σ₁ − σ₂ is tiny relative to the distance to the limit, so there is no 0/0 at σ₁ = σ₂.
///
/// PSD: h(σ) = b(s − σ) is convex and non-decreasing in σ, zero below s − ŝ > 0, so the energy
/// is a convex function of F (Lewis 1995, convex unitarily invariant functions), hence of x
/// (F is linear in x). The exact element Hessian is therefore PSD, and the projected Hessian is
/// the exact one (no eigen-decomposition; PSD up to rounding).
class StrainLimit : public StencilTerm<3> {
 public:
  /// @param rest rest positions (|V| × 3), m
  /// @param faces triangles (|F| × 3), indices into rest
  /// @param face_limits strain limit s_f > 1 of each face (|F|), e.g. 1.06
  /// @param band activation band ŝ, 0 < ŝ < s_f − 1 for every face
  /// @param stiffness κ > 0, Pa·m
  /// @throws Error(invalid_argument) if face_limits.size() ≠ |F|, a limit is not > 1, the band
  ///         is out of range or the stiffness is not > 0 (or any of them is non-finite);
  ///         Error(invalid_mesh) if a face index is out of range or a rest triangle has zero
  ///         (or non-finite) area.
  StrainLimit(const Positions& rest, const Faces& faces, std::vector<double> face_limits,
              double band, double stiffness);

  const char* name() const override { return "strain_limit"; }

  /// Largest singular value σ₁ of F over all faces at x (3|V|); 0 for a mesh without faces.
  /// @throws Error(invalid_argument) if x.size() ≠ 3|V|.
  double max_stretch(const Vector& x) const;

  /// The faces (indices into this term's faces) with σ₁ ≥ their own limit s_f at x (3|V|).
  /// @throws Error(invalid_argument) if x.size() ≠ 3|V|.
  std::vector<int> faces_beyond_limit(const Vector& x) const;

  /// κ (Pa·m).
  double stiffness() const { return stiffness_; }
  /// Sets κ. Not thread-safe with a concurrent evaluation.
  /// @throws Error(invalid_argument) unless stiffness > 0 and finite.
  void set_stiffness(double stiffness);

  /// ŝ.
  double band() const { return band_; }
  /// s_f of face f (raised by fit_limits() while a start beyond the limit is relaxed).
  double limit(int f) const { return elements_[f].limit; }
  /// What moved the state since the last fit_limits call.
  enum class FitAfter {
    solve,   ///< a solve (or nothing yet): a face that did not come down is held
    motion,  ///< prescribed motion (handles moved): no face is judged held
  };
  /// Limit homotopy for a start beyond some faces' limits (what prescribed motion stretched, or
  /// what a refined start's strain correction, correct_strain(), could not bring under): a face
  /// with σ₁ ≥ its limit gets the limit σ₁ + ŝ/2 (inside the barrier's band, so it pulls the face
  /// back); on later calls, after a solve, a raised limit comes down halfway to the face's σ₁,
  /// never below the face's own s_f. Faces under their s_f keep it. Call after each solve until it
  /// returns 0; returns the faces whose limit is still raised. Not thread-safe with a concurrent
  /// evaluation.
  ///
  /// A load can hold a face near its raised limit: the barrier then balances the load at a gap
  /// d ≈ κĀŝ²/f from the limit, and halving the gap of a face that does not move halves the
  /// Newton steps (a log barrier's step is of the gap's size) until they fall below the Newton
  /// tolerance and the face stops for good (faces next to the drape's pinned centre stayed at
  /// stretch 1.12–1.16 over 1.06 for hundreds of solves). A face still beyond its own limit
  /// whose σ₁ came down by less than a quarter of its gap (under ŝ) since the last call is
  /// therefore held: its limit is set to σ₁ + ŝ/2 instead and its barrier stiffened fourfold
  /// (barrier_scale), which widens d fourfold, until it moves; the scale returns to 1 with the
  /// face's own limit. Only a call after a solve judges that (`after`): prescribed motion moves
  /// faces by itself.
  int fit_limits(const Vector& x, FitAfter after = FitAfter::solve);
  /// Multiplier of κ on face f (1 unless fit_limits stiffened a held face's barrier).
  double barrier_scale(int f) const { return elements_[f].scale; }
  /// Rest area Ā of face f (m²).
  double rest_area(int f) const { return elements_[f].area; }

 protected:
  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;
  /// The exact Hessian, which is PSD (see the class comment).
  void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

 private:
  /// Throws Error(invalid_argument), naming `what`, unless x.size() = 3|V|.
  void check_size(const Vector& x, const char* what) const;
  /// Per-face constants. F = Σ_a x_a β_aᵀ (3×2), β_a the rows of `beta`.
  struct Element {
    Eigen::Matrix<double, 3, 2> beta;  ///< ∂F/∂x_a = I₃ ⊗ β_aᵀ; rows sum to zero
    double area;                       ///< Ā (m²)
    double limit;                      ///< the limit in force (s_f unless fit_limits raised it)
    double own_limit;                  ///< s_f
    double scale = 1.0;                ///< multiplier of κ (fit_limits: held faces)
    double fitted_stretch = 0.0;       ///< σ₁ at the last fit_limits call
    /// Ā times the scale: the face's weight in κ Ā scale Σ_i b.
    double weight() const { return area * scale; }
  };

  std::vector<Element> elements_;
  double band_;
  double stiffness_;
  int num_vertices_;
};

}  // namespace progsim
