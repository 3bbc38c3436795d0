// Pressure: enclosed volume of sphere meshes, gradient as area-weighted vertex normals,
// derivatives against finite differences, rigid-motion invariance, PSD projection.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <random>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "energy/pressure.hpp"
#include "mesh/mesh_generators.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;
using pt::eigenvalues;
using pt::perturbed;
using pt::rigidly_moved;
using pt::varied_materials;

TEST(Pressure, SphereVolumeConvergesToFourThirdsPiRCubed) {
  const double r = 0.7, exact = 4.0 / 3.0 * kPi * r * r * r;
  double previous_error = 1.0;
  for (int s = 1; s <= 4; ++s) {
    const TriangleMesh sphere = make_sphere(r, s);
    const Pressure term(sphere.vertices, sphere.faces, 0.0);
    EXPECT_TRUE(term.closed());
    const double v = term.volume(as_dofs(sphere.vertices));
    const double error = (exact - v) / exact;
    EXPECT_GT(error, 0.0) << "an inscribed polyhedron is smaller than the sphere";
    EXPECT_LT(error, previous_error / 3.0) << "second-order convergence in the edge length";
    previous_error = error;
  }
  EXPECT_LT(previous_error, 3e-3);
}

TEST(Pressure, ValueIsMinusPressureTimesVolumeAndGradientTheAreaWeightedNormals) {
  const TriangleMesh sphere = make_sphere(0.5, 2);
  Pressure term(sphere.vertices, sphere.faces, 0.0);
  EXPECT_EQ(term.value(as_dofs(sphere.vertices)), 0.0);
  term.set_pressure(2500.0);
  EXPECT_EQ(term.pressure(), 2500.0);
  EXPECT_STREQ(term.name(), "pressure");
  const Vector x = perturbed(sphere.vertices, 0.03, 1);
  EXPECT_NEAR(term.value(x), -2500.0 * term.volume(x), 1e-12 * std::abs(term.value(x)));
  // ∂V/∂x_i = (1/3) Σ_{f ∋ i} A_f n̂_f on a closed surface: computed here face by face.
  Vector normals = Vector::Zero(x.size());
  for (int f = 0; f < sphere.num_faces(); ++f) {
    const Vec3 a = x.segment<3>(3 * sphere.faces(f, 0)), b = x.segment<3>(3 * sphere.faces(f, 1)),
               c = x.segment<3>(3 * sphere.faces(f, 2));
    const Vec3 area_normal = 0.5 * (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normals.segment<3>(3 * sphere.faces(f, k)) += area_normal / 3.0;
  }
  EXPECT_LT(pt::relative_error(pt::analytic_gradient(term, x), -2500.0 * normals, 1e-15), 1e-12);
}

TEST(Pressure, DerivativesMatchFiniteDifferences) {
  const TriangleMesh sphere = make_sphere(0.5, 1);
  const TriangleMesh sheet = make_grid(1.0, 1.0, 3, 3);  // open: cone volume from o
  for (const TriangleMesh& mesh : {sphere, sheet}) {
    const Pressure term(mesh.vertices, mesh.faces, 1e3);
    for (unsigned seed : {2u, 3u}) {
      SCOPED_TRACE(seed);
      const Vector x = perturbed(mesh.vertices, 0.08, seed);
      const Vector g = pt::analytic_gradient(term, x);
      EXPECT_LT(pt::relative_error(g, pt::finite_difference_gradient(term, x, 1e-6), 1e-15), 1e-8);
      const Eigen::MatrixXd h = pt::assembled_hessian(term, x, false);
      EXPECT_LT(pt::relative_error(h, pt::finite_difference_hessian(term, x, 1e-6), 1e-15), 1e-8);
      EXPECT_LT((h - h.transpose()).cwiseAbs().maxCoeff(), 1e-12 * h.cwiseAbs().maxCoeff());
    }
  }
}

TEST(Pressure, ClosedSurfaceIsInvariantUnderRigidMotion) {
  const TriangleMesh sphere = make_sphere(0.5, 1);
  const Pressure term(sphere.vertices, sphere.faces, -700.0);
  const Vector x = perturbed(sphere.vertices, 0.05, 4);
  const Mat3 r = pt::random_rotation(5);
  const Vector y = rigidly_moved(x, r, Vec3(3.0, -2.0, 10.0));
  EXPECT_NEAR(term.value(y), term.value(x), 1e-11 * std::abs(term.value(x)));
  EXPECT_LT(
      pt::relative_error(pt::analytic_gradient(term, y),
                         rigidly_moved(pt::analytic_gradient(term, x), r, Vec3::Zero()), 1e-15),
      1e-10);
  // The projected Hessian is taken about the current centroid, so it moves with the body.
  const Vector z = rigidly_moved(x, Mat3::Identity(), Vec3(30.0, -20.0, 100.0));
  EXPECT_LT(pt::relative_error(pt::assembled_hessian(term, z, true),
                               pt::assembled_hessian(term, x, true), 1e-15),
            1e-9);
}

TEST(Pressure, ProjectedHessianIsPsd) {
  const TriangleMesh sphere = make_sphere(0.5, 1);
  Pressure term(sphere.vertices, sphere.faces, 1e3);
  const Vector x = perturbed(sphere.vertices, 0.05, 6);
  const Eigen::MatrixXd exact = pt::assembled_hessian(term, x, false);
  EXPECT_LT(eigenvalues(exact).minCoeff(), -1e-3 * eigenvalues(exact).maxCoeff());
  const Eigen::VectorXd projected = eigenvalues(pt::assembled_hessian(term, x, true));
  EXPECT_GE(projected.minCoeff(), -1e-8 * projected.maxCoeff());
  EXPECT_GT(projected.maxCoeff(), 0.0);
  // The projection clamps small per-edge matrices, so it stays as small as the exact Hessian;
  // per-face matrices about a fixed point would be larger by about radius / edge length.
  const Eigen::VectorXd exact_eigenvalues = eigenvalues(exact);
  const double exact_scale = std::max(exact_eigenvalues.maxCoeff(), -exact_eigenvalues.minCoeff());
  std::cout << "[ pressure ] largest eigenvalue: projected " << projected.maxCoeff() << ", exact "
            << exact_scale << std::endl;
  EXPECT_LT(projected.maxCoeff(), 1.5 * exact_scale);
  // With p = 0 the (zero) Hessian is PSD and the projection leaves it alone.
  term.set_pressure(0.0);
  EXPECT_EQ(pt::assembled_hessian(term, x, true).cwiseAbs().maxCoeff(), 0.0);
}

TEST(Pressure, OrientationAndIndicesAreChecked) {
  TriangleMesh sphere = make_sphere(0.5, 1);
  sphere.faces.col(1).swap(sphere.faces.col(2));  // inward normals
  EXPECT_THROW(Pressure(sphere.vertices, sphere.faces, 1.0), Error);
  TriangleMesh bad = make_sphere(0.5, 0);
  bad.faces(3, 1) = 12;
  EXPECT_THROW(Pressure(bad.vertices, bad.faces, 1.0), Error);
  const TriangleMesh sheet = make_grid(1.0, 1.0, 2, 2);
  EXPECT_FALSE(Pressure(sheet.vertices, sheet.faces, 1.0).closed());
}
