#pragma once
/// @file The surfaces contact acts on: the simulated shell, whose vertices are the DOFs, and
/// the scripted obstacles, whose vertices are not, as one indexed triangle set.
#include <array>
#include <string>
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// Collision vertex v < num_shell_vertices is shell vertex v (DOFs 3v..3v+2); the others are
/// obstacle vertices, whose positions the contact terms hold themselves.
struct CollisionMesh {
  int num_shell_vertices = 0;
  int num_obstacle_vertices = 0;
  int num_shell_faces = 0;                ///< the first faces are the shell's
  Faces faces;                            ///< (|F| × 3) collision vertex indices
  std::vector<std::array<int, 2>> edges;  ///< unique edges (i < j)
  std::vector<double> vertex_offset;      ///< ξ_v: half the shell thickness, 0 on obstacles (m)
  std::vector<double> vertex_friction;    ///< μ_v of the surface the vertex belongs to
  Positions rest;                         ///< (|V| × 3) rest positions (edge–edge mollifier)
  /// The vertices that meet faces and the ground as points, ascending: those a face uses. A
  /// shell vertex no face uses (inside a tetrahedral solid) never collides.
  std::vector<int> points;
  int num_shell_points = 0;  ///< the first num_shell_points entries of points are shell vertices

  int num_vertices() const { return num_shell_vertices + num_obstacle_vertices; }
  bool is_obstacle(int v) const { return v >= num_shell_vertices; }
  /// Largest offset over all vertices (m).
  double max_offset() const;
};

/// "shell vertex 12" or "obstacle vertex 3" (obstacle vertices numbered from 0), for messages.
std::string describe_vertex(const CollisionMesh& mesh, int v);
/// "shell face 12" or "obstacle face 3", for messages.
std::string describe_face(const CollisionMesh& mesh, int f);

/// An obstacle surface to merge into a collision mesh.
struct ObstacleSurface {
  const Positions* positions;  ///< (|V| × 3) positions at t = 0
  const Faces* faces;          ///< (|F| × 3) indices into positions
  double friction;             ///< μ of its surface
};

/// Merges the shell (its vertices, in order, are the DOFs; vertices none of its faces use, such as
/// a solid's interior, are DOFs without contact) and the obstacles.
/// @param shell_offset per shell vertex ξ (m), e.g. half the thickness of its body
/// @param shell_friction per shell vertex μ
CollisionMesh build_collision_mesh(const Positions& shell_rest, const Faces& shell_faces,
                                   const std::vector<double>& shell_offset,
                                   const std::vector<double>& shell_friction,
                                   const std::vector<ObstacleSurface>& obstacles);

}  // namespace progsim
