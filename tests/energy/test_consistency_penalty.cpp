// The consistency penalty of progressive dynamics (VPD eq. 4): its value against the closed
// form and its derivatives against finite differences.
#include <gtest/gtest.h>

#include "energy/consistency_penalty.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
using namespace progsim::test_support;

TEST(ConsistencyPenalty, IsTheWeightedMassNormOfTheDistanceToItsTarget) {
  const Eigen::VectorXd masses = Eigen::Vector3d(0.5, 1.0, 2.0);
  const double weight = 0.25, h = 0.02;
  ConsistencyPenalty penalty(masses, weight, h);
  EXPECT_STREQ(penalty.name(), "consistency_penalty");
  const Vector target = Vector::LinSpaced(9, -1.0, 1.0);
  penalty.set_target(target);
  Vector x = target;
  x.segment<3>(3) += Vec3(0.1, -0.2, 0.3);  // vertex 1 (mass 1) off by 0.14 m²
  EXPECT_NEAR(penalty.value(x), weight / (2 * h * h) * 1.0 * 0.14, 1e-12);  // w/(2h²)‖x − y‖²_M
  penalty.set_target(perturbed(Positions::Random(3, 3), 0.1, 3));
  expect_derivatives_match_finite_differences(penalty, perturbed(Positions::Random(3, 3), 0.1, 7),
                                              1e-6, 1e-6);
}
