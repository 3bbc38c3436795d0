#include "energy/tet_lumped_mass.hpp"

#include <Eigen/LU>

namespace progsim {

Eigen::VectorXd lumped_tet_masses(const Positions& rest, const Tets& tets,
                                  const std::vector<SolidMaterial>& tet_materials) {
  Eigen::VectorXd masses = Eigen::VectorXd::Zero(rest.rows());
  for (Eigen::Index t = 0; t < tets.rows(); ++t) {
    Mat3 d;
    for (int k = 0; k < 3; ++k)
      d.col(k) = (rest.row(tets(t, k + 1)) - rest.row(tets(t, 0))).transpose();
    const double quarter = tet_materials[t].density * d.determinant() / 24.0;  // ρ (det D̄ / 6) / 4
    for (int k = 0; k < 4; ++k) masses[tets(t, k)] += quarter;
  }
  return masses;
}

}  // namespace progsim
