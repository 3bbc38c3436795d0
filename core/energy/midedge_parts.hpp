#pragma once
/// @file Pieces the mid-edge bending energies share (MidedgeBending, FittedMidedgeBending): the
/// hinge quantity 2 h sin(θ/2) with its derivatives, a face's constant stiffness, the vertices
/// across a face's edges, and the curvature of a quadratic fitted over a face and its flaps.
#include <array>
#include <vector>

#include "common/types.hpp"
#include "energy/dihedral_angle.hpp"
#include "energy/shell_material.hpp"
#include "mesh/mesh_topology.hpp"

namespace progsim::midedge {

using Vector9 = Eigen::Matrix<double, 9, 1>;
using Matrix9 = Eigen::Matrix<double, 9, 9>;

/// The height h = ‖e × w‖/‖e‖ (m) of x2 over the line x0 x1 with ∇h (9) and ∇²h (9 × 9) in
/// (x0, x1, x2), e = x1 − x0, w = x2 − x0.
struct EdgeHeight {
  Vector9 gradient;
  Matrix9 hessian;
  EdgeHeight(const Vec3& e, const Vec3& w);
};

/// 2 h sin(θ/2) (m) of the hinge (x0, x1, x2, x3) (12): h the height of x2 over the edge x0 x1,
/// θ its signed dihedral angle (dihedral_angle(); both orderings of a hinge seen from either
/// face give the same θ); with ∇ (12) and ∇² (12 × 12) if asked.
double height_sine(const Vector12& xh, Vector12* gradient, Matrix12* hessian);

/// Bending Young's modulus E_b (Pa): bending_youngs_modulus when set, E otherwise.
double bending_modulus(const ShellMaterial& m);

/// Q (J/m²) with ½ Δsᵀ Q Δs = c [(α/2) tr²(M) + β tr(M²)], M = ā⁻¹ B(Δs),
/// B(Δs) = −(Δs₀ [[1,1],[1,1]] + Δs₁ [[1,0],[0,0]] + Δs₂ [[0,0],[0,1]]) (Grinspun et al. 2006's
/// mid-edge shape operator in the basis (q1 − q0, q2 − q0)), c = t³ Ā/12, for a face of rest
/// positions q0, q1, q2 and material m. Error(invalid_mesh) naming face f at zero rest area.
Mat3 face_stiffness(const Vec3& q0, const Vec3& q1, const Vec3& q2, const ShellMaterial& m, int f);

/// What lies across each edge of a face: per corner k, the edge opposite it.
struct Across {
  std::array<int, 3> vertex{-1, -1, -1};  ///< the neighbour's vertex off the edge; −1: boundary
  std::array<int, 3> face{-1, -1, -1};    ///< the neighbouring face; −1: boundary
};

/// Per face, what lies across its edges, from the hinges. Error(invalid_argument) if there are
/// not one material per face, a face's vertex index is outside [0, num_vertices) or a hinge
/// does not match its faces.
std::vector<Across> faces_across(const Faces& faces, const std::vector<Hinge>& hinges,
                                 int num_vertices, std::size_t num_materials);

/// The curvature of a quadratic fitted through a face (q0, q1, q2) and the vertices p_k across
/// its edges (the rotation-free plate triangle of Phaal & Calladine 1992): κ = Σ_k η_k K_k in
/// Cartesian coordinates of the face's plane, η_k the height of p_k over the plane. Across a
/// boundary edge (no p_k) the free edge's condition κ_nn + ν κ_tt = 0 stands in, and K_k = 0.
struct QuadraticFit {
  std::array<Mat2, 3> curvatures;  ///< K_k (1/m²); zero unless `unique`
  std::array<Vec2, 3> corners;     ///< q0, q1, q2 in the plane's coordinates (q0 at the origin)
  /// False where the six points admit no well-conditioned quadratic (the fit's smallest
  /// singular value below 1e-6 of its largest: e.g. all six on one circle, or a degenerate
  /// face).
  bool unique = false;
  /// @param x q0, q1, q2, p0, p1, p2 at rest (p_k ignored where !interior[k])
  QuadraticFit(const std::array<Vec3, 6>& x, const std::array<bool, 3>& interior, double nu);
};

}  // namespace progsim::midedge
