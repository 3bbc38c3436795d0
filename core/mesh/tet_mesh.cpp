#include "mesh/tet_mesh.hpp"

#include <Eigen/Geometry>

namespace progsim {

Eigen::VectorXd tet_signed_volumes(const Positions& vertices, const Tets& tets) {
  Eigen::VectorXd volumes(tets.rows());
  for (Eigen::Index t = 0; t < tets.rows(); ++t) {
    const Vec3 x0 = vertices.row(tets(t, 0));
    const Vec3 e1 = vertices.row(tets(t, 1)).transpose() - x0;
    const Vec3 e2 = vertices.row(tets(t, 2)).transpose() - x0;
    const Vec3 e3 = vertices.row(tets(t, 3)).transpose() - x0;
    volumes[t] = e1.dot(e2.cross(e3)) / 6.0;
  }
  return volumes;
}

double tet_mesh_volume(const TetMesh& mesh) {
  return tet_signed_volumes(mesh.vertices, mesh.tets).sum();
}

}  // namespace progsim
