#pragma once
/// @file The boundary surface of a tet mesh: the triangle faces that belong to one tet only.
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "mesh/triangle_mesh.hpp"

namespace progsim {

/// A tet mesh's boundary as a triangle mesh of its own, with the way back to the volume.
struct TetBoundary {
  TriangleMesh surface;            ///< the boundary vertices and faces, normals outward
  std::vector<int> volume_vertex;  ///< surface vertex i is tet mesh vertex volume_vertex[i]
  std::vector<int> face_tet;       ///< surface face f belongs to tet face_tet[f]
};

/// Extracts the faces used by exactly one tet, each ordered so that its right-hand normal points
/// out of its tet, with the vertices they use only; volume_vertex is increasing, so the surface
/// keeps the tet mesh's vertex order. For a mesh that passes validate_tet_mesh the surface
/// passes validate_mesh (a closed, consistently oriented 2-manifold with outward normals).
/// Faces are in order of their sorted vertex indices. Precondition: indices lie in [0, |V|) and
/// no tet repeats a vertex (the mesh need not be otherwise valid).
TetBoundary extract_tet_boundary(const TetMesh& mesh);

/// The boundary faces of extract_tet_boundary() indexing the tet mesh's own vertices (|F| × 3),
/// the faces of a solid body (scene.hpp). Same precondition.
Faces tet_boundary_faces(const TetMesh& mesh);

}  // namespace progsim
