#pragma once
/// @file A tetrahedral volume mesh: positions and tets, nothing else.
///
/// Orientation convention, used by every tet function of progsim: tet (x0, x1, x2, x3) is
/// positively oriented if (x1 − x0) · ((x2 − x0) × (x3 − x0)) > 0, that is, if x3 lies on the
/// side of triangle (x0, x1, x2) that its right-hand normal (x1 − x0) × (x2 − x0) points to.
/// The four faces (x1, x2, x3), (x0, x3, x2), (x0, x1, x3), (x0, x2, x1) then have outward
/// right-hand normals. This is also the convention of Gmsh and of VTK's VTK_TETRA (cell type 10).
#include "common/types.hpp"

namespace progsim {

/// A tetrahedral mesh. Validated meshes (validate_tet_mesh) have positively oriented tets.
struct TetMesh {
  Positions vertices;  ///< (|V| × 3), metres
  Tets tets;           ///< (|T| × 4), indices into vertices

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_tets() const { return static_cast<int>(tets.rows()); }
};

/// Signed volume of each tet (|T|), m³: (x1 − x0) · ((x2 − x0) × (x3 − x0)) / 6, positive for
/// the orientation convention above. Precondition: indices lie in [0, |V|).
Eigen::VectorXd tet_signed_volumes(const Positions& vertices, const Tets& tets);

/// Sum of the signed volumes of the tets, m³: the volume the mesh fills if it is valid.
double tet_mesh_volume(const TetMesh& mesh);

}  // namespace progsim
