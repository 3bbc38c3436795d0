#include "mesh/triangle_mesh.hpp"

#include <Eigen/Geometry>

namespace progsim {

double bounding_box_diagonal(const Positions& vertices) {
  if (vertices.rows() == 0) return 0.0;
  return (vertices.colwise().maxCoeff() - vertices.colwise().minCoeff()).norm();
}

Eigen::VectorXd face_areas(const Positions& vertices, const Faces& faces) {
  Eigen::VectorXd areas(faces.rows());
  for (int f = 0; f < faces.rows(); ++f) {
    const Vec3 a = vertices.row(faces(f, 0)).transpose();
    const Vec3 e1 = vertices.row(faces(f, 1)).transpose() - a;
    const Vec3 e2 = vertices.row(faces(f, 2)).transpose() - a;
    areas[f] = 0.5 * e1.cross(e2).norm();
  }
  return areas;
}

TriangleMesh merge_meshes(const std::vector<const TriangleMesh*>& parts) {
  Eigen::Index nv = 0, nf = 0;
  for (const TriangleMesh* part : parts) {
    nv += part->vertices.rows();
    nf += part->faces.rows();
  }
  TriangleMesh merged{Positions(nv, 3), Faces(nf, 3)};
  Eigen::Index v = 0, f = 0;
  for (const TriangleMesh* part : parts) {
    merged.vertices.middleRows(v, part->vertices.rows()) = part->vertices;
    merged.faces.middleRows(f, part->faces.rows()) = part->faces.array() + static_cast<int>(v);
    v += part->vertices.rows();
    f += part->faces.rows();
  }
  return merged;
}

}  // namespace progsim
