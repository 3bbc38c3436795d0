#include "contact/collision_mesh.hpp"

#include <algorithm>

#include "mesh/mesh_topology.hpp"

namespace progsim {

double CollisionMesh::max_offset() const {
  return vertex_offset.empty() ? 0.0
                               : *std::max_element(vertex_offset.begin(), vertex_offset.end());
}

std::string describe_vertex(const CollisionMesh& mesh, int v) {
  return mesh.is_obstacle(v) ? "obstacle vertex " + std::to_string(v - mesh.num_shell_vertices)
                             : "shell vertex " + std::to_string(v);
}

std::string describe_face(const CollisionMesh& mesh, int f) {
  return f < mesh.num_shell_faces ? "shell face " + std::to_string(f)
                                  : "obstacle face " + std::to_string(f - mesh.num_shell_faces);
}

CollisionMesh build_collision_mesh(const Positions& shell_rest, const Faces& shell_faces,
                                   const std::vector<double>& shell_offset,
                                   const std::vector<double>& shell_friction,
                                   const std::vector<ObstacleSurface>& obstacles) {
  CollisionMesh mesh;
  mesh.num_shell_vertices = static_cast<int>(shell_rest.rows());
  mesh.num_shell_faces = static_cast<int>(shell_faces.rows());
  mesh.vertex_offset = shell_offset;
  mesh.vertex_friction = shell_friction;
  Eigen::Index num_faces = shell_faces.rows();
  for (const ObstacleSurface& o : obstacles) {
    mesh.num_obstacle_vertices += static_cast<int>(o.positions->rows());
    num_faces += o.faces->rows();
  }
  Positions& rest = mesh.rest;
  rest.resize(mesh.num_vertices(), 3);
  rest.topRows(shell_rest.rows()) = shell_rest;
  mesh.faces.resize(num_faces, 3);
  mesh.faces.topRows(shell_faces.rows()) = shell_faces;
  Eigen::Index vertex = shell_rest.rows(), face = shell_faces.rows();
  for (const ObstacleSurface& o : obstacles) {
    rest.middleRows(vertex, o.positions->rows()) = *o.positions;
    mesh.faces.middleRows(face, o.faces->rows()) = o.faces->array() + static_cast<int>(vertex);
    mesh.vertex_offset.insert(mesh.vertex_offset.end(), o.positions->rows(), 0.0);
    mesh.vertex_friction.insert(mesh.vertex_friction.end(), o.positions->rows(), o.friction);
    vertex += o.positions->rows();
    face += o.faces->rows();
  }
  mesh.edges = build_topology(mesh.faces, mesh.num_vertices()).edges;
  std::vector<char> used(mesh.num_vertices(), 0);
  for (Eigen::Index i = 0; i < mesh.faces.size(); ++i) used[mesh.faces.data()[i]] = 1;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (used[v]) mesh.points.push_back(v);
  mesh.num_shell_points = static_cast<int>(
      std::lower_bound(mesh.points.begin(), mesh.points.end(), mesh.num_shell_vertices) -
      mesh.points.begin());
  return mesh;
}

}  // namespace progsim
