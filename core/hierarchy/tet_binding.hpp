#pragma once
/// @file Binding the vertices of one tet mesh to the tets of another that overlaps it without
/// conforming (VPD §3.3.2–3.3.3): the containing tet where there is one, else a home tet found
/// by the topology-aware rule, with barycentric weights that are negative outside it.
#include <Eigen/Core>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace progsim {

/// How a fine vertex was bound.
enum class BindingKind {
  /// it lies in its tet: closed, by CGAL's exact orientation predicates, or within 1e-9 of it in
  /// barycentric weights (a vertex a mesher left an ulp outside a shared boundary plane)
  inside,
  ray,       ///< outside: the first coarse boundary face hit by a ray along an incident edge
  neighbor,  ///< outside, no ray hit: the closest of its bound neighbours' tets
  nearest,   ///< outside, no hit and no bound neighbour: the tet of the nearest boundary face
};

/// A fine vertex's home: x = Σ_k w_k X_{T_k} over the corners of coarse tet T.
struct TetBinding {
  int tet = -1;             ///< coarse tet index
  Eigen::Vector4d weights;  ///< barycentric weights, summing to 1; negative outside T
  BindingKind kind = BindingKind::inside;
};

/// Binds every vertex of `fine` to a tet of `coarse` (VPD §3.3.3): vertices inside a coarse tet
/// to it; then, repeatedly, the unbound vertex with the most bound neighbours (fine tet edges)
/// casts rays from itself through each neighbour and takes the tet behind the closest coarse
/// boundary face hit; with no hit, the closest tet among its bound neighbours' homes; a vertex
/// with neither takes the tet of the nearest coarse boundary face. Neighbouring fine vertices so
/// never bind across a gap of the coarse mesh (two prongs, a slit) that Euclidean nearest-tet
/// binding (Georgii and Westermann 2006) would bind across.
/// Preconditions: both meshes pass validate_tet_mesh. Deterministic.
std::vector<TetBinding> bind_to_tets(const TetMesh& coarse, const TetMesh& fine);

/// Barycentric weights of point p in tet t of `mesh` (4, summing to 1).
Eigen::Vector4d tet_barycentric_weights(const TetMesh& mesh, int t, const Eigen::Vector3d& p);

}  // namespace progsim
