#pragma once
/// @file Thin-shell bending from the mid-edge discrete shape operator (Grinspun, Gingold,
/// Reisman & Zorin 2006, "Computing discrete shape operators on general meshes"), as the
/// elastic shell energy of Chen, Sastry, van Rees & Vouga 2018, "Physical simulation of
/// environmentally induced thin shell deformation" (their "MidedgeAverage" variant).
#include <array>
#include <vector>

#include "energy/edge_quadratic_bending.hpp"
#include "energy/shell_material.hpp"
#include "mesh/mesh_topology.hpp"

namespace progsim {
namespace midedge {
struct Across;
}  // namespace midedge

/// Bending energy summed over faces f with vertices (q0, q1, q2):
///   E_f = (t³/12) Ā_f [ (α/2) tr²(M) + β tr(M²) ],   M = ā⁻¹ (b − b̄)
/// (the bending part of Chen et al. 2018's discrete energy; equation numbers not checked against
/// the paper, whose text was not at hand: the formulas follow Evouga's libshell, BSD), with ā the
/// rest first fundamental form in the basis (q̄1 − q̄0, q̄2 − q̄0), b the second fundamental form built
/// from the three mid-edge normals, b̄ its rest value (curved rest shapes carry no force),
/// Ā_f the rest area, α = E_b ν/(1 − ν²), β = E_b/(2(1 + ν)) (so that a uniformly bent
/// plate stores the Kirchhoff energy (D/2)[(κ₁ + κ₂)² − 2(1 − ν)κ₁κ₂] per area,
/// D = E_b t³/(12(1 − ν²))).
///
/// The mid-edge normal m_i of the edge opposite q_i is the bisector of the two adjacent unit
/// face normals (libshell normalises the sum of the area-weighted normals instead: on a
/// perturbed grid rolled into a cylinder that measured 1.13 × the plate energy at 160 cells
/// against the bisector's 1.07, and the bisector keeps s_i bounded at a full fold); on a
/// boundary edge it is the face's own normal. Interpolating the
/// normals linearly from the edge midpoints gives (Grinspun et al. 2006; libshell's
/// MidedgeAverageFormulation, up to the overall sign, which the quadratic energy does not see)
///   b = −[[s₀ + s₁, s₀], [s₀, s₀ + s₂]],  s_i = m_i · (q_{i+1} + q_{i+2} − 2 q_i),
/// and since m_i bisects the hinge, s_i = 2 h_i sin(θ_i/2) with h_i the current height of q_i
/// over its opposite edge and θ_i the hinge's signed dihedral angle (zero on a boundary).
/// The energy is thus ½ (s − s̄)ᵀ Q_f (s − s̄) with a constant 3×3 Q_f per face.
///
/// Each element is a face and the three vertices across its edges (18 DOFs). Derivatives are
/// exact and closed-form (∇θ, ∇²θ as in HingeBending; h from ‖e × w‖²/‖e‖²), finite while the
/// current faces have non-zero area. PSD projection: the per-element eigenvalue clamp, or the
/// Gauss–Newton Jᵀ Q J (EdgeQuadraticBending::set_gauss_newton; dynamic scenes).
///
/// Accuracy (tests/sim/test_bending_convergence.cpp): a cantilever under its weight matches
/// beam theory to 0.2 % on right-triangle grids of either diagonal pattern, but is 5–6 % too
/// stiff on an irregular (randomly perturbed) grid without converging, as averaged edge normals
/// are not consistent there (Grinspun et al. 2006 add a per-edge normal DOF for that).
class MidedgeBending : public EdgeQuadraticBending<6> {
 public:
  /// @param rest rest positions (|V| × 3), m; defines ā, Ā and b̄
  /// @param faces triangles (|F| × 3), consistently oriented
  /// @param hinges interior edges of `faces` (see Hinge), as from build_topology()
  /// @param face_materials one material per face (|F|): E (or E_b), ν, thickness t (m)
  /// @throws Error(invalid_argument) if face_materials.size() ≠ |F|, an index is out of range
  ///         or a hinge does not match its faces; Error(invalid_mesh) if a rest face has zero
  ///         area.
  MidedgeBending(const Positions& rest, const Faces& faces, const std::vector<Hinge>& hinges,
                 const std::vector<ShellMaterial>& face_materials);

  using EdgeQuadraticBending<6>::rest_edge_values;

 protected:
  /// s (m) of face e at xe, optionally with ∇s_i (18) and ∇²s_i (18 × 18) per edge.
  Vec3 edge_values(int e, const LocalVector& xe, LocalVector* gradients,
                   LocalMatrix* hessians) const override;

 private:
  /// The public constructor's, with what lies across each face's edges found once.
  MidedgeBending(const Positions& rest, const Faces& faces,
                 const std::vector<ShellMaterial>& face_materials,
                 const std::vector<midedge::Across>& across);

  std::vector<std::array<bool, 3>> interior_;  ///< per face and edge: has a neighbouring face
};

}  // namespace progsim
