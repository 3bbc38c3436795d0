#pragma once
/// @file Thin-shell bending from the mid-edge shape operator with each edge's normal fitted to
/// the curvature around it, so that it converges on irregular meshes as well as regular ones.
#include <array>
#include <vector>

#include "energy/edge_quadratic_bending.hpp"
#include "energy/shell_material.hpp"
#include "mesh/mesh_topology.hpp"

namespace progsim {
namespace midedge {
struct Across;
}  // namespace midedge

/// Bending energy summed over faces f (q0, q1, q2), as MidedgeBending's
///   E_f = ½ (s − s̄)ᵀ Q_f (s − s̄),  s_i = 2 h_i sin(θ_i/2 + φ_i),
/// (h_i the current height of q_i over its opposite edge, θ_i that edge's dihedral angle, Q_f
/// the constant stiffness of Grinspun et al. 2006's mid-edge shape operator), with the edge's
/// normal turned by φ_i from the bisector that MidedgeBending takes.
///
/// Why: the shape operator is exact for a quadratic surface when each mid-edge normal is the
/// surface's normal at the edge's midpoint (Stokes' theorem over the face: ∇w is linear, so
/// its edge averages are its midpoint values), and it passes the patch test when the two faces
/// of an edge share that normal. The bisector is that normal only where the two faces form a
/// parallelogram. For a quadratic w with Hessian H (small slopes, edge of length L with
/// midpoint m and tangent t, ν its in-plane normal towards f, d_f = q_i − m at height h_f and
/// d_g the neighbour's far vertex at height h_g on the other side), the slope of face f across
/// the edge exceeds the surface's by ψ_f = Q_f(H)/h_f with Q(H) = ½ dᵀ H d − (L²/8) H_tt
/// (Taylor expansion of w about m; our derivation), and the dihedral angle is θ = ψ_f + ψ_g.
/// The surface's normal thus lies at θ/2 + φ_f from face f, φ_f = ½ (ψ_f − ψ_g). H is
/// estimated as the mean of the two faces' quadratic fits (midedge::QuadraticFit: each face
/// with the three vertices across its edges, exact for quadratics), whose heights are taken as
/// 2 ℓ sin(θ/2) (ℓ the far vertex's height over the hinge's edge; to first order its height
/// over the face's plane, and bounded at a full fold). So φ_i is a constant linear combination
/// of twelve hinge quantities of the face's 12-vertex neighbourhood, and shared: φ_g = −φ_f.
/// Boundary edges keep the face's own normal (s_i = 0), as MidedgeBending does; an edge where
/// either face's fit is not unique (its six points on one conic, e.g. one circle) keeps the
/// bisector (φ = 0).
///
/// Each element is a face, the three vertices across its edges and, for each neighbour, the
/// two vertices across its other edges (36 DOFs; missing ones repeat a face vertex and carry
/// no derivative). Derivatives are exact and closed form (chain rule through the hinge
/// quantities of MidedgeBending). PSD projection: the per-element eigenvalue clamp, or the
/// Gauss–Newton Jᵀ Q J (EdgeQuadraticBending::set_gauss_newton; dynamic scenes).
class FittedMidedgeBending : public EdgeQuadraticBending<12> {
 public:
  /// @param rest rest positions (|V| × 3), m; defines Q_f, s̄ and the fits
  /// @param faces triangles (|F| × 3), consistently oriented
  /// @param hinges interior edges of `faces` (see Hinge), as from build_topology()
  /// @param face_materials one material per face (|F|): E (or E_b), ν, thickness t (m)
  /// @throws Error(invalid_argument) if face_materials.size() ≠ |F|, an index is out of range
  ///         or a hinge does not match its faces; Error(invalid_mesh) if a rest face has zero
  ///         area.
  FittedMidedgeBending(const Positions& rest, const Faces& faces, const std::vector<Hinge>& hinges,
                       const std::vector<ShellMaterial>& face_materials);

  using EdgeQuadraticBending<12>::rest_edge_values;

 protected:
  /// s (m) of face e at xe, optionally with ∇s_i (36) and ∇²s_i (36 × 36) per edge.
  Vec3 edge_values(int e, const LocalVector& xe, LocalVector* gradients,
                   LocalMatrix* hessians) const override;

 private:
  /// The public constructor's, with what lies across each face's edges found once.
  FittedMidedgeBending(const Positions& rest, const Faces& faces,
                       const std::vector<ShellMaterial>& face_materials,
                       const std::vector<midedge::Across>& across);

  /// The twelve hinge quantities τ_j of an element (see the .cpp) that φ combines.
  static constexpr int kQuantities = 12;
  /// How a face's edge normals are turned.
  struct Turn {
    std::array<bool, 3> interior;                   ///< per edge opposite q_i: has a neighbour
    Eigen::Matrix<double, 3, kQuantities> weights;  ///< φ_i = Σ_j weights(i, j) τ_j
    std::array<bool, kQuantities> used;             ///< τ_j enters some φ_i
  };

  std::vector<Turn> turns_;
};

}  // namespace progsim
