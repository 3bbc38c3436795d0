#pragma once
/// @file Discrete hinge bending energy of a thin shell (Grinspun et al. 2003, "Discrete
/// Shells"; derivatives after Bridson et al. 2003 and Tamstorf & Grinspun 2013; DESIGN.md §2).
#include <vector>

#include "energy/dihedral_angle.hpp"
#include "energy/shell_material.hpp"
#include "energy/stencil_term.hpp"
#include "mesh/mesh_topology.hpp"

namespace progsim {

/// How HingeBending projects its element Hessians onto the PSD cone.
enum class HingeProjection {
  /// Exact per-element eigenvalue clamp (projected Newton, DESIGN.md §2). Default.
  eigenvalue_clamp,
  /// 2c ∇θ∇θᵀ: drops the (always indefinite) curvature term 2c(θ − θ̄)∇²θ. PSD, equal to the
  /// exact Hessian at θ = θ̄ and ~60× cheaper than the clamp, but it also drops the geometric
  /// stiffness of bent hinges, so bending-dominated solves may converge much more slowly.
  gauss_newton,
};

/// Bending energy over the interior edges (hinges) e of a triangle mesh:
///   E(x) = Σ_e k_e (θ_e − θ̄_e)² · ‖ē‖² / (Ā₁ + Ā₂),
/// with θ the signed dihedral angle (see dihedral_angle()), θ̄ its rest value (so curved rest
/// shapes carry no force), ‖ē‖ the rest edge length, Ā₁, Ā₂ the rest areas of the two faces
/// and k_e = E t³/(24(1 − ν²)) averaged over the two faces. θ − θ̄ is wrapped to (−π, π], so
/// the energy stays continuous when a hinge folds through ±π (it has a kink at θ − θ̄ = ±π).
///
/// Derivatives are closed-form: ∇θ after Bridson et al. 2003 and ∇²θ from differentiating it
/// exactly (the same quantities as Tamstorf & Grinspun 2013). Derivatives are finite as long as
/// both current faces have non-zero area; a degenerate face gives non-finite derivatives (the
/// membrane's infinite energy keeps a line search away from such states).
/// The default PSD projection is the exact 12×12 eigenvalue clamp, computed in the 8-dimensional
/// complement of the Hessian's known null space (rigid translations and stretching along the
/// edge); see HingeProjection for a cheaper alternative.
class HingeBending : public StencilTerm<4> {
 public:
  /// @param rest rest positions (|V| × 3), m; defines θ̄, ‖ē‖ and Ā
  /// @param faces triangles (|F| × 3); only used to check the hinges against
  /// @param hinges interior edges (see Hinge): edge v0 → v1 in face f0 = (v0, v1, v2),
  ///        face f1 = (v1, v0, v3)
  /// @param face_materials one material per face (|F|): E (Pa), ν, thickness t (m)
  /// @throws Error(invalid_argument) if face_materials.size() ≠ |F| or a hinge does not match
  ///         its faces; Error(invalid_mesh) if a hinge's rest faces have zero area.
  HingeBending(const Positions& rest, const Faces& faces, const std::vector<Hinge>& hinges,
               const std::vector<ShellMaterial>& face_materials);

  const char* name() const override { return "bending"; }

  /// Rest dihedral angle θ̄ of hinge e (radians).
  double rest_angle(int e) const { return elements_[e].rest_angle; }
  /// Stiffness of hinge e: k_e · ‖ē‖²/(Ā₁ + Ā₂) (J per rad²).
  double stiffness(int e) const { return elements_[e].stiffness; }
  /// Chooses how hessian_values(x, true, ·) projects (default: eigenvalue_clamp).
  void set_projection(HingeProjection projection) { projection_ = projection; }
  /// The projection hessian_values(x, true, ·) uses.
  HingeProjection projection() const { return projection_; }

 protected:
  double element_value(int e, const LocalVector& xe) const override;
  void element_gradient(int e, const LocalVector& xe, LocalVector& g) const override;
  void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;
  void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const override;

 private:
  struct Element {
    double rest_angle;  ///< θ̄ (rad)
    double stiffness;   ///< k_e · ‖ē‖²/(Ā₁ + Ā₂) (J)
  };
  /// θ − θ̄ wrapped to (−π, π].
  double angle_change(int e, const LocalVector& xe) const;

  std::vector<Element> elements_;
  HingeProjection projection_ = HingeProjection::eigenvalue_clamp;
};

}  // namespace progsim
