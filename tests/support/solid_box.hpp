#pragma once
/// @file A solid (tet) box body for tests that simulate volumetric bodies.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <utility>

#include "mesh/tet_boundary.hpp"
#include "mesh/tet_generators.hpp"
#include "scene/scene.hpp"

namespace progsim::test_support {

/// A solid box body named "solid" of nx × ny × nz cells (make_tet_box, centred at the origin),
/// its rest shape moved by `shift`, of density 1000 kg/m³ and the given E (Pa), ν and model.
inline Body solid_box(const Vec3& size, int nx, int ny, int nz, const Vec3& shift, double e,
                      double nu, SolidModel model) {
  TetMesh m = make_tet_box(size, nx, ny, nz);
  m.vertices.rowwise() += shift.transpose();
  Body b;
  b.name = "solid";
  b.mesh.faces = tet_boundary_faces(m);
  b.mesh.vertices = m.vertices;
  b.tets = m.tets;
  b.material.youngs_modulus = e;
  b.material.poisson_ratio = nu;
  b.material.density = 1000.0;
  b.solid_model = model;
  return b;
}

/// Smallest det of the tets' edge matrices at positions x (|V| × 3, any Eigen rows expression):
/// positive when no tet is inverted or flat.
template <class Rows>
double min_tet_determinant(const Tets& tets, const Rows& x) {
  double lowest = INFINITY;
  for (Eigen::Index t = 0; t < tets.rows(); ++t) {
    Mat3 d;
    for (int k = 0; k < 3; ++k) d.col(k) = (x.row(tets(t, k + 1)) - x.row(tets(t, 0))).transpose();
    lowest = std::min(lowest, d.determinant());
  }
  return lowest;
}

}  // namespace progsim::test_support
