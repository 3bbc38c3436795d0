#include "mesh/tet_boundary.hpp"

#include "mesh/tet_faces.hpp"

namespace progsim {

TetBoundary extract_tet_boundary(const TetMesh& mesh) {
  TetBoundary boundary;
  const Faces faces = boundary_faces(sorted_tet_faces(mesh.tets), mesh.tets, &boundary.face_tet);
  std::vector<int> surface_vertex(mesh.num_vertices(), -1);
  for (Eigen::Index i = 0; i < faces.size(); ++i) surface_vertex[faces.data()[i]] = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (surface_vertex[v] < 0) continue;
    surface_vertex[v] = static_cast<int>(boundary.volume_vertex.size());
    boundary.volume_vertex.push_back(v);
  }
  const int n = static_cast<int>(boundary.volume_vertex.size());
  boundary.surface.vertices.resize(n, 3);
  for (int i = 0; i < n; ++i)
    boundary.surface.vertices.row(i) = mesh.vertices.row(boundary.volume_vertex[i]);
  boundary.surface.faces = faces.unaryExpr([&](int v) { return surface_vertex[v]; });
  return boundary;
}

Faces tet_boundary_faces(const TetMesh& mesh) {
  return boundary_faces(sorted_tet_faces(mesh.tets), mesh.tets);
}

}  // namespace progsim
