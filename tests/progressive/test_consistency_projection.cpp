// ConsistencyProjection (VPD App. C eq. 19): the mass-weighted projection of a fine state onto
// the coarse level, checked by hand on a three-vertex line.
#include <gtest/gtest.h>

#include <cmath>

#include "progressive/consistency_projection.hpp"

namespace progsim {
namespace {

/// Fine vertices 0, 1, 2 at coarse vertex 0, halfway between 0 and 1, and at 1; coarse vertex
/// 2 binds no fine vertex (a zero column, as a coarse tet vertex whose tets hold none).
ProlongationMatrix line_prolongation() {
  ProlongationMatrix u(3, 3);
  u.insert(0, 0) = 1.0;
  u.insert(1, 0) = 0.5;
  u.insert(1, 1) = 0.5;
  u.insert(2, 1) = 1.0;
  u.makeCompressed();
  return u;
}

Vector dofs(std::initializer_list<double> values) {
  Vector v(values.size());
  int i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

TEST(ConsistencyProjection, UnboundCoarseVerticesAreLeftOutOfTheProjectionAndTheNorm) {
  const Eigen::Vector3d fine_masses(1.0, 2.0, 1.0), coarse_masses(2.0, 2.0, 5.0);
  const ConsistencyProjection projection(line_prolongation(), fine_masses, coarse_masses);
  // Coarse state y (vertex 2 anywhere), fine state U y: Π U y = y on the bound vertices.
  const Vector coarse = dofs({0, 0, 0, 1, 2, 3, 7, 7, 7});
  const Vector fine = dofs({0, 0, 0, 0.5, 1, 1.5, 1, 2, 3});
  EXPECT_NEAR(projection.distance(fine, coarse), 0.0, 1e-14);
  // Coarse vertex 0 off by d along x: sqrt(m_0 d² / (m_0 + m_1)) = d / √2 (vertex 2's mass of 5
  // is not in the denominator).
  Vector moved = coarse;
  moved[0] += 0.3;
  EXPECT_NEAR(projection.distance(fine, moved), 0.3 / std::sqrt(2.0), 1e-14);
}

TEST(ConsistencyProjection, ProjectsAFineStateTheCoarseLevelCannotHoldByLeastSquares) {
  // Fine vertex 1 lifted by h along z off the line U y: the normal equations UᵀMU Π = UᵀM x with
  // M = diag(1, 2, 1) give UᵀMU = [[1.5, 0.5], [0.5, 1.5]] and UᵀM x = (h, h) along z, so both
  // coarse vertices rise by h / 2 and the distance to y is h / 2.
  const Eigen::Vector3d fine_masses(1.0, 2.0, 1.0), coarse_masses(2.0, 2.0, 5.0);
  const ConsistencyProjection projection(line_prolongation(), fine_masses, coarse_masses);
  const double h = 0.4;
  const Vector coarse = dofs({0, 0, 0, 1, 0, 0, 0, 0, 0});
  const Vector fine = dofs({0, 0, 0, 0.5, 0, h, 1, 0, 0});
  EXPECT_NEAR(projection.distance(fine, coarse), h / 2.0, 1e-14);
}

}  // namespace
}  // namespace progsim
