// WindForce: derivatives against finite differences, a positive semi-definite Hessian, and the
// force on a plate against the drag equation and the lift's closed form.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "energy/wind_force.hpp"
#include "mesh/mesh_generators.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;

namespace {

constexpr double kTimeStep = 0.01;
const AirCoefficients kAir{1.2, 1.1, 0.7};

/// Random velocities of size n in [−amplitude, amplitude].
Vector random_velocities(Eigen::Index n, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
  Vector v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = uniform(rng);
  return v;
}

/// A 1 m × 1 m plate (two triangles) in the xy plane, turned by `degrees` about the x axis.
TriangleMesh unit_plate(double degrees) {
  TriangleMesh plate = make_grid(1.0, 1.0, 1, 1);
  const Mat3 r = Eigen::AngleAxisd(degrees * kPi / 180.0, Vec3::UnitX()).toRotationMatrix();
  for (Eigen::Index i = 0; i < plate.vertices.rows(); ++i)
    plate.vertices.row(i) = (r * plate.vertices.row(i).transpose()).transpose();
  return plate;
}

/// The term for `mesh` lagged at its rest shape at rest, in wind w.
WindForce plate_term(const TriangleMesh& mesh, const AirCoefficients& air, const Vec3& w) {
  WindForce term(mesh.faces, mesh.num_vertices(), air);
  const Vector rest = as_dofs(mesh.vertices);
  term.lag(rest, Vector::Zero(rest.size()), kTimeStep, w);
  return term;
}

}  // namespace

TEST(WindForce, DerivativesMatchFiniteDifferences) {
  const TriangleMesh sheet = make_grid(0.6, 0.4, 3, 2);
  WindForce term(sheet.faces, sheet.num_vertices(), kAir);
  const Vector start = pt::perturbed(sheet.vertices, 0.05, 1);
  term.lag(start, random_velocities(start.size(), 2.0, 2), kTimeStep, Vec3(3.0, -1.0, 8.0));
  const Vector x = start + kTimeStep * random_velocities(start.size(), 4.0, 3);
  EXPECT_STREQ(term.name(), "wind");
  pt::expect_derivatives_match_finite_differences(term, x, 1e-7, 1e-5, 1e-9);
}

TEST(WindForce, HessianIsPositiveSemidefiniteAndItsOwnProjection) {
  const TriangleMesh sheet = make_grid(0.6, 0.4, 3, 2);
  WindForce term(sheet.faces, sheet.num_vertices(), kAir);
  const Vector start = pt::perturbed(sheet.vertices, 0.05, 4);
  term.lag(start, random_velocities(start.size(), 2.0, 5), kTimeStep, Vec3(-4.0, 2.0, 6.0));
  const Vector x = start + kTimeStep * random_velocities(start.size(), 4.0, 6);
  const Eigen::MatrixXd exact = pt::assembled_hessian(term, x, false);
  const Eigen::VectorXd lambda = pt::eigenvalues(exact);
  ASSERT_GT(lambda.maxCoeff(), 0.0);
  EXPECT_GE(lambda.minCoeff(), -1e-12 * lambda.maxCoeff());
  EXPECT_EQ(pt::assembled_hessian(term, x, true), exact);
}

TEST(WindForce, PlateAcrossTheWindFeelsTheDragEquation) {
  const double speed = 5.0;
  const TriangleMesh plate = unit_plate(0.0);
  const WindForce term = plate_term(plate, kAir, Vec3(0.0, 0.0, speed));
  const Vector x = as_dofs(plate.vertices);
  const Vec3 expected(0.0, 0.0, 0.5 * kAir.density * kAir.drag * 1.0 * speed * speed);  // ½ρC_dAU²
  EXPECT_LT((term.total_force(x) - expected).norm(), 1e-12 * expected.norm());  // no lift across
  const Vector gradient = pt::analytic_gradient(term, x);
  Vec3 sum = Vec3::Zero();
  for (int v = 0; v < plate.num_vertices(); ++v) sum -= gradient.segment<3>(3 * v);
  EXPECT_LT((sum - expected).norm(), 1e-12 * expected.norm()) << "the force is −∇E";
}

TEST(WindForce, TiltedPlateFeelsDragAlongItsNormalAndLiftAcrossTheWind) {
  const double speed = 5.0, q = 0.5 * kAir.density * speed * speed;  // dynamic pressure ½ρU²
  const TriangleMesh plate = unit_plate(45.0);
  const Vec3 u(0.0, 0.0, speed), n = Vec3(0.0, -1.0, 1.0).normalized();
  const WindForce with_lift = plate_term(plate, kAir, u);
  const WindForce without_lift = plate_term(plate, {kAir.density, kAir.drag, 0.0}, u);
  const Vector x = as_dofs(plate.vertices);
  const Vec3 drag = without_lift.total_force(x), lift = with_lift.total_force(x) - drag;
  EXPECT_LT((drag - q * kAir.drag * 0.5 * n).norm(), 1e-12 * q);  // ½ρC_dA (U cos 45°)² n
  EXPECT_NEAR(lift.norm(), q * kAir.lift * 0.5, 1e-12 * q);       // ½ρC_LAU² cos 45° sin 45°
  EXPECT_NEAR(lift.dot(u), 0.0, 1e-12 * q * speed) << "across the wind";
  EXPECT_NEAR(lift.dot(n.cross(u)), 0.0, 1e-12 * q * speed) << "in the plane of u and n";
  EXPECT_GT(lift.dot(drag), 0.0) << "toward the side the pressure pushes";
}

TEST(WindForce, FaceOrientationDoesNotMatter) {
  TriangleMesh plate = unit_plate(30.0), flipped = plate;
  flipped.faces.col(1).swap(flipped.faces.col(2));
  const Vec3 w(1.0, -2.0, 4.0);
  const Vector x = as_dofs(plate.vertices);
  const Vec3 force = plate_term(plate, kAir, w).total_force(x);
  EXPECT_LT((plate_term(flipped, kAir, w).total_force(x) - force).norm(), 1e-12 * force.norm());
}

TEST(WindForce, RejectsAFaceIndexOutOfRange) {
  Faces faces(1, 3);
  faces << 0, 1, 3;
  EXPECT_THROW(WindForce(faces, 3, kAir), Error);
}
