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

}  // namespace progsim
