#pragma once
/// @file A triangle surface mesh: positions and faces, nothing else.
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// A triangle mesh. Faces are consistently oriented (counter-clockwise seen from the side
/// the normal points to). Validated meshes have no unreferenced vertices.
struct TriangleMesh {
  Positions vertices;  ///< (|V| × 3), metres
  Faces faces;         ///< (|F| × 3), indices into vertices

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_faces() const { return static_cast<int>(faces.rows()); }
};

/// Length of the diagonal of the axis-aligned bounding box of the vertices (metres).
double bounding_box_diagonal(const Positions& vertices);

/// Area of each face (|F|), m².
Eigen::VectorXd face_areas(const Positions& vertices, const Faces& faces);

/// The meshes `parts` as one: their vertices and faces in order, face indices shifted.
TriangleMesh merge_meshes(const std::vector<const TriangleMesh*>& parts);

}  // namespace progsim
