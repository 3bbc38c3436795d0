#include "energy/lumped_mass.hpp"

#include "mesh/triangle_mesh.hpp"

namespace progsim {

Eigen::VectorXd lumped_vertex_masses(const Positions& rest, const Faces& faces,
                                     const std::vector<ShellMaterial>& face_materials) {
  const Eigen::VectorXd areas = face_areas(rest, faces);
  Eigen::VectorXd masses = Eigen::VectorXd::Zero(rest.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const ShellMaterial& m = face_materials[f];
    const double third = m.density * m.thickness * areas[f] / 3.0;  // ρ t A / 3
    for (int k = 0; k < 3; ++k) masses[faces(f, k)] += third;
  }
  return masses;
}

Eigen::VectorXd lumped_vertex_areas(const Positions& rest, const Faces& faces) {
  const Eigen::VectorXd areas = face_areas(rest, faces);
  Eigen::VectorXd lumped = Eigen::VectorXd::Zero(rest.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) lumped[faces(f, k)] += areas[f] / 3.0;  // A / 3
  return lumped;
}

}  // namespace progsim
