// max_handle_step(): the fraction of a scripted handle step after which a face next to the
// handle has lost the allowed share of its area, against closed forms on one triangle.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/handle_step_bound.hpp"

using namespace progsim;

namespace {

/// The triangle (0,0,0), (1,0,0), (0,1,0): area vector (0, 0, 1).
Vector unit_triangle() {
  Vector x(9);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  return x;
}

/// The step moving vertex 1 by d1 and vertex 2 by d2 (vertex 0 stays).
Vector step_of(const Vec3& d1, const Vec3& d2) {
  Vector d = Vector::Zero(9);
  d.segment<3>(3) = d1;
  d.segment<3>(6) = d2;
  return d;
}

const Faces kFace = (Faces(1, 3) << 0, 1, 2).finished();

}  // namespace

TEST(HandleStepBound, LinearShrinkStopsWhereHalfTheAreaIsLeft) {
  // Vertex 2 moved by (0, −2, 0): n(α) = (0, 0, 1 − 2α), half the area at α = ¼.
  const Vector d = step_of(Vec3::Zero(), Vec3(0, -2, 0));
  EXPECT_NEAR(max_handle_step(kFace, unit_triangle(), d, 0.5), 0.25, 1e-15);
  EXPECT_NEAR(max_handle_step(kFace, unit_triangle(), d, 0.2), 0.4, 1e-15);
  // a step that keeps more than half goes all the way
  EXPECT_EQ(max_handle_step(kFace, unit_triangle(), 0.2 * d, 0.5), 1.0);
}

TEST(HandleStepBound, QuadraticShrinkStopsAtItsFirstRoot) {
  // Vertices 1 and 2 moved toward vertex 0: n(α) = (0, 0, (1 − 2α)²) = ½ at α = (1 − √½)/2.
  const Vector d = step_of(Vec3(-2, 0, 0), Vec3(0, -2, 0));
  EXPECT_NEAR(max_handle_step(kFace, unit_triangle(), d, 0.5), 0.5 * (1.0 - std::sqrt(0.5)), 1e-15);
  // n(α) = (0, 0, 1 + α²): a shear that only grows the area is never bounded
  EXPECT_EQ(max_handle_step(kFace, unit_triangle(), step_of(Vec3(0, 1, 0), Vec3(-1, 0, 0)), 0.5),
            1.0);
}

TEST(HandleStepBound, TurningAwayCountsLikeShrinking) {
  // Vertex 2 swung to (0, 0, 1) − a quarter turn about x: n(α)·n = 1 − α (linear in α for
  // this chord), so half the projected area is left at α = ½.
  const Vector d = step_of(Vec3::Zero(), Vec3(0, -1, 1));
  EXPECT_NEAR(max_handle_step(kFace, unit_triangle(), d, 0.5), 0.5, 1e-15);
}

TEST(HandleStepBound, FacesMovedWholeOrNotAtAllAreNotBounded) {
  Vector whole = Vector::Zero(9);
  for (int v = 0; v < 3; ++v) whole.segment<3>(3 * v) = Vec3(5, 0, 0);
  whole.segment<3>(6) = Vec3(5, -3, 0);  // even one that collapses: the script's own face
  EXPECT_EQ(max_handle_step(kFace, unit_triangle(), whole, 0.5), 1.0);
  EXPECT_EQ(max_handle_step(kFace, unit_triangle(), Vector::Zero(9), 0.5), 1.0);
}
