// Mid-edge bending (Grinspun et al. 2006 shape operator, Chen et al. 2018 energy), with edge
// normals that bisect their faces (MidedgeBending) or are fitted to the curvature around them
// (FittedMidedgeBending): derivatives against finite differences, zero force at a curved rest
// shape, rigid-motion invariance, the PSD projection, and the energy of sheets rolled into
// cylinders and bent into quadratic shapes against plate theory.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "energy/fitted_midedge_bending.hpp"
#include "energy/midedge_bending.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh/triangle_mesh.hpp"
#include "support/energy_checks.hpp"
#include "support/rolled_sheets.hpp"

using namespace progsim;
namespace mt = progsim::test_support;

namespace {

template <class Term>
Term make_term(const TriangleMesh& rest, const std::vector<ShellMaterial>& materials) {
  return Term(rest.vertices, rest.faces, build_topology(rest.faces, rest.num_vertices()).hinges,
              materials);
}

MidedgeBending make_midedge(const TriangleMesh& rest, const std::vector<ShellMaterial>& materials) {
  return make_term<MidedgeBending>(rest, materials);
}

/// Kirchhoff plate energy of a cylinder of radius r over area a: (D/2) a / r²,
/// D = E t³/(12(1 − ν²)) (the other principal curvature is held at 0).
double cylinder_plate_energy(const ShellMaterial& m, double area, double r) {
  const double d = m.youngs_modulus * std::pow(m.thickness, 3) /
                   (12.0 * (1.0 - m.poisson_ratio * m.poisson_ratio));
  return 0.5 * d * area / (r * r);
}

}  // namespace

/// The mid-edge terms, with bisected or fitted edge normals.
template <class Term>
class MidedgeTerms : public ::testing::Test {};
using MidedgeModels = ::testing::Types<MidedgeBending, FittedMidedgeBending>;
TYPED_TEST_SUITE(MidedgeTerms, MidedgeModels);

TYPED_TEST(MidedgeTerms, DerivativesMatchFiniteDifferencesAtRandomStates) {
  const TriangleMesh grid = make_grid(1.0, 1.0, 3, 3);
  const TriangleMesh patch = make_cylinder(0.4, 0.6, 2.0, 4, 3);
  for (const auto& [mesh, edge] : {std::pair{grid, 1.0 / 3.0}, std::pair{patch, 0.2}}) {
    const TypeParam term = make_term<TypeParam>(mesh, mt::varied_materials(mesh.num_faces(), 21));
    EXPECT_STREQ(term.name(), "bending");
    for (unsigned seed : {1u, 2u, 3u}) {
      SCOPED_TRACE(seed);
      const Vector x = mt::perturbed(mesh.vertices, 0.25 * edge, seed);
      mt::expect_derivatives_match_finite_differences(term, x, 1e-6 * edge, 1e-6, 1e-15, 1e-12);
    }
  }
}

TYPED_TEST(MidedgeTerms, CurvedRestShapeHasZeroEnergyAndForce) {
  const TriangleMesh patch = make_cylinder(0.4, 0.6, 2.0, 4, 3);
  const TriangleMesh dome = make_sphere(0.5, 2);
  for (const TriangleMesh& mesh : {patch, dome}) {
    const TypeParam term = make_term<TypeParam>(mesh, mt::varied_materials(mesh.num_faces(), 22));
    const Vector x = as_dofs(mesh.vertices);
    EXPECT_GT(term.rest_edge_values(0).norm(), 0.01);  // curved: s̄ ≠ 0
    EXPECT_EQ(term.value(x), 0.0);
    EXPECT_EQ(mt::analytic_gradient(term, x).cwiseAbs().maxCoeff(), 0.0);
    const Vector y = mt::rigidly_moved(x, mt::random_rotation(23), Vec3(1.0, 2.0, -0.5));
    EXPECT_LT(term.value(y), 1e-24);
    EXPECT_LT(mt::analytic_gradient(term, y).cwiseAbs().maxCoeff(), 1e-14);
  }
  // The flat sheet with the patch's connectivity is not at rest.
  const TypeParam term = make_term<TypeParam>(patch, mt::varied_materials(patch.num_faces(), 22));
  EXPECT_GT(mt::analytic_gradient(term, as_dofs(make_grid(1.0, 0.6, 4, 3).vertices)).norm(), 1e-6);
}

TYPED_TEST(MidedgeTerms, InvariantUnderRigidMotion) {
  const TriangleMesh patch = make_cylinder(0.4, 0.6, 2.0, 4, 3);
  const TypeParam term = make_term<TypeParam>(patch, mt::varied_materials(patch.num_faces(), 24));
  const Vector x = mt::perturbed(patch.vertices, 0.05, 25);
  const Mat3 r = mt::random_rotation(26);
  const Vector y = mt::rigidly_moved(x, r, Vec3(-0.4, 0.9, 3.0));
  EXPECT_GT(term.value(x), 0.0);
  EXPECT_NEAR(term.value(y), term.value(x), 1e-12 * term.value(x));
  EXPECT_LT(
      mt::relative_error(mt::analytic_gradient(term, y),
                         mt::rigidly_moved(mt::analytic_gradient(term, x), r, Vec3::Zero()), 1e-15),
      1e-10);
}

TYPED_TEST(MidedgeTerms, ProjectedHessianIsPsdAndExactAtRest) {
  const TriangleMesh patch = make_cylinder(0.4, 0.6, 2.0, 4, 3);
  const TypeParam term = make_term<TypeParam>(patch, mt::varied_materials(patch.num_faces(), 27));
  const Vector x = mt::perturbed(patch.vertices, 0.05, 28);
  const Eigen::VectorXd exact = mt::eigenvalues(mt::assembled_hessian(term, x, false));
  const Eigen::VectorXd projected = mt::eigenvalues(mt::assembled_hessian(term, x, true));
  EXPECT_LT(exact.minCoeff(), -1e-6 * exact.maxCoeff()) << "state should be indefinite";
  EXPECT_GE(projected.minCoeff(), -1e-8 * projected.maxCoeff());
  const Vector at_rest = as_dofs(patch.vertices);
  const Eigen::MatrixXd h = mt::assembled_hessian(term, at_rest, false);
  EXPECT_GT(h.norm(), 0.0);
  EXPECT_LT(mt::relative_error(mt::assembled_hessian(term, at_rest, true), h, 1e-15), 1e-12);
}

TEST(MidedgeBending, GridRolledAlongItsAxisCarriesThePlateEnergy) {
  // Rest flat, current a cylinder of radius R (isometric: all energy is bending, with the
  // other principal curvature held at 0). Kirchhoff: (D/2) A / R², D = E t³/(12(1 − ν²)),
  // for ν = 0 and ν = 0.3 alike (measured: the same ratios to 1e-6). Boundary edges keep the
  // face normal (s_i = 0), which misprices the boundary rows of faces: an O(h) error that must
  // shrink under refinement (0.898, 0.949, 0.975, 0.987 at nx = 10, 20, 40, 80).
  // Oblique axes on this right-triangle grid are another matter: the average of two face
  // normals picks up the twist where the centroids' offset is not normal to the edge, and the
  // energy stays 37 % (30°) and 49 % (45°) too high under refinement at ν = 0, 48 % and 64 % at
  // ν = 0.3 (printed, not asserted;
  // the equilateral test below has no such offsets). Hinge bending
  // prices these oblique cylinders the same way (1.37 and 1.50 at nx = 80, HingeBending tests).
  const double width = 0.5, length = 0.3, radius = 0.4;
  for (double nu : {0.0, 0.3}) {
    ShellMaterial m;
    m.poisson_ratio = nu;
    double previous_error = 1.0;
    for (int nx : {10, 20, 40, 80}) {
      const TriangleMesh flat = make_grid(width, length, nx, nx * 3 / 5);
      const MidedgeBending term =
          make_midedge(flat, std::vector<ShellMaterial>(flat.num_faces(), m));
      const double plate = cylinder_plate_energy(m, width * length, radius);
      const double ratio = term.value(mt::rolled(flat, radius, 0.0)) / plate;
      std::cout << "[ midedge  ] grid, nu = " << nu << ", nx = " << nx << ": E/E_plate = " << ratio
                << " (axis along y), " << term.value(mt::rolled(flat, radius, kPi / 6)) / plate
                << " (30 deg), " << term.value(mt::rolled(flat, radius, kPi / 4)) / plate
                << " (45 deg)" << std::endl;
      const double error = std::abs(ratio - 1.0);
      EXPECT_LT(error, 0.6 * previous_error) << "nx = " << nx;
      previous_error = error;
    }
    EXPECT_LT(previous_error, 0.015);
  }
}

TYPED_TEST(MidedgeTerms, GaussNewtonProjectionIsPsdAndExactAtRest) {
  // Jᵀ Q J (dynamic scenes): PSD everywhere, the exact Hessian at rest, and not the exact one
  // (nor its clamp) away from it, where the second derivatives of s are left out.
  const TriangleMesh patch = make_cylinder(0.4, 0.6, 2.0, 4, 3);
  TypeParam term = make_term<TypeParam>(patch, mt::varied_materials(patch.num_faces(), 31));
  term.set_gauss_newton(true);
  const Vector x = mt::perturbed(patch.vertices, 0.05, 32);
  const Eigen::MatrixXd gn = mt::assembled_hessian(term, x, true);
  const Eigen::VectorXd eigenvalues = mt::eigenvalues(gn);
  EXPECT_GE(eigenvalues.minCoeff(), -1e-8 * eigenvalues.maxCoeff());
  EXPECT_GT(mt::relative_error(gn, mt::assembled_hessian(term, x, false), 1e-15), 1e-3);
  const Vector at_rest = as_dofs(patch.vertices);
  EXPECT_LT(mt::relative_error(mt::assembled_hessian(term, at_rest, true),
                               mt::assembled_hessian(term, at_rest, false), 1e-15),
            1e-12);
}

TYPED_TEST(MidedgeTerms, RejectsBadInput) {
  const TriangleMesh mesh = make_grid(1.0, 1.0, 2, 2);
  const std::vector<Hinge> hinges = build_topology(mesh.faces, mesh.num_vertices()).hinges;
  const std::vector<ShellMaterial> materials(mesh.num_faces());
  EXPECT_THROW(TypeParam(mesh.vertices, mesh.faces, hinges, std::vector<ShellMaterial>(1)), Error);
  std::vector<Hinge> swapped = hinges;
  std::swap(swapped[0].v2, swapped[0].v3);
  EXPECT_THROW(TypeParam(mesh.vertices, mesh.faces, swapped, materials), Error);
  Faces out_of_range = mesh.faces;
  out_of_range(0, 0) = 99;
  EXPECT_THROW(TypeParam(mesh.vertices, out_of_range, hinges, materials), Error);
  Positions degenerate = mesh.vertices;
  degenerate.row(mesh.faces(0, 1)) = degenerate.row(mesh.faces(0, 0));
  try {
    TypeParam(degenerate, mesh.faces, hinges, materials);
    ADD_FAILURE() << "no error for a degenerate rest face";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::invalid_mesh);
  }
}

TYPED_TEST(MidedgeTerms, EquilateralSheetRolledIntoCylinderCarriesThePlateEnergy) {
  // Rows of equilateral triangles (edge a = 1/40), rolled about axes at several angles: the
  // ratio to (D/2) A / R² is near 1 for every axis (the boundary rows cost O(a)).
  const TriangleMesh sheet = mt::equilateral_sheet(40);
  const double radius = 0.5;
  ShellMaterial m;
  m.poisson_ratio = 0.0;
  const TypeParam term =
      make_term<TypeParam>(sheet, std::vector<ShellMaterial>(sheet.num_faces(), m));
  const double plate =
      cylinder_plate_energy(m, face_areas(sheet.vertices, sheet.faces).sum(), radius);
  std::cout << "[ midedge  ] equilateral, E/E_plate:";
  for (double alpha : {0.0, kPi / 12, kPi / 6, kPi / 4, kPi / 2}) {
    const double ratio = term.value(mt::rolled(sheet, radius, alpha)) / plate;
    std::cout << " " << ratio;
    EXPECT_NEAR(ratio, 1.0, 0.03) << "axis at " << alpha << " rad";  // measured 0.978–0.988
  }
  std::cout << std::endl;
}

TYPED_TEST(MidedgeTerms, PoissonRatioCouplesTheTwoCurvaturesAsInKirchhoffPlates) {
  // z = ½(κ₁ x² + κ₂ y²) with small κ (the metric changes by O(κ² x²) < 1 %): Kirchhoff's
  // energy per area (D/2)[(κ₁ + κ₂)² − 2(1 − ν) κ₁κ₂], D = E t³/(12(1 − ν²)), ν = 0.3.
  // A sphere-like (κ₂ = κ₁), a cylinder (κ₂ = 0) and the anticlastic shape a free strip takes
  // under an end moment (κ₂ = −ν κ₁), whose energy is the lowest of all κ₂ for that κ₁.
  const TriangleMesh sheet = mt::equilateral_sheet(40);
  ShellMaterial m;
  m.poisson_ratio = 0.3;
  const TypeParam term =
      make_term<TypeParam>(sheet, std::vector<ShellMaterial>(sheet.num_faces(), m));
  const double d = m.youngs_modulus * std::pow(m.thickness, 3) / (12.0 * (1.0 - 0.09));
  const double area = face_areas(sheet.vertices, sheet.faces).sum();
  const double k1 = 0.1;
  double lowest = 1e9, lowest_k2 = 0.0;
  std::cout << "[ midedge  ] nu = 0.3, E/E_plate for k2/k1 =";
  for (double ratio : {1.0, 0.0, -0.3, -0.6}) {
    const double k2 = ratio * k1;
    Vector x = as_dofs(sheet.vertices);
    for (int v = 0; v < sheet.num_vertices(); ++v) {
      const double px = sheet.vertices(v, 0) - 0.5, py = sheet.vertices(v, 1) - 0.5;
      x[3 * v + 2] = 0.5 * (k1 * px * px + k2 * py * py);
    }
    const double plate =
        0.5 * d * area * ((k1 + k2) * (k1 + k2) - 2.0 * (1.0 - m.poisson_ratio) * k1 * k2);
    const double energy = term.value(x);
    std::cout << " " << ratio << ": " << energy / plate;
    EXPECT_NEAR(energy / plate, 1.0, 0.03) << "k2/k1 = " << ratio;
    if (energy < lowest) {
      lowest = energy;
      lowest_k2 = ratio;
    }
  }
  std::cout << std::endl;
  EXPECT_EQ(lowest_k2, -0.3);
}

TEST(FittedMidedgeBending, SheetsRolledAboutAnyAxisConvergeToThePlateEnergy) {
  // The right-triangle grid of MidedgeBending's test above and the same grid with its interior
  // vertices moved by up to 0.2 of a cell, rolled about axes at 0°, 30° and 45° (ν = 0.3):
  // fitted normals converge for every axis and mesh, only the boundary rows' O(h) remaining,
  // where bisected normals stay 48–64 % high at oblique axes on the grid.
  const double width = 0.5, length = 0.3, radius = 0.4;
  ShellMaterial m;
  m.poisson_ratio = 0.3;
  const double plate = cylinder_plate_energy(m, width * length, radius);
  for (double jitter : {0.0, 0.2}) {
    for (double axis : {0.0, kPi / 6, kPi / 4}) {
      double previous_error = 1.0;
      std::cout << "[ fitted   ] jitter " << jitter << ", axis " << axis << " rad: E/E_plate";
      for (int nx : {10, 20, 40, 80}) {
        const TriangleMesh flat = mt::jittered_grid(width, length, nx, nx * 3 / 5, jitter);
        const std::vector<ShellMaterial> materials(flat.num_faces(), m);
        const double ratio =
            make_term<FittedMidedgeBending>(flat, materials).value(mt::rolled(flat, radius, axis)) /
            plate;
        std::cout << " " << ratio;
        const double error = std::abs(ratio - 1.0);
        EXPECT_LT(error, 0.7 * previous_error) << "nx = " << nx;
        previous_error = error;
      }
      std::cout << std::endl;
      EXPECT_LT(previous_error, 0.03);
    }
  }
}

TEST(FittedMidedgeBending, EdgesWithoutAUniqueFitKeepTheBisector) {
  // A regular hexagon meshed as a central triangle and three ears: the central face and the
  // three vertices across its edges lie on one circle, so no unique quadratic passes through
  // them. The term still builds, and every interior edge keeps the bisector: the energy is
  // MidedgeBending's.
  TriangleMesh hexagon;
  hexagon.vertices.resize(6, 3);
  for (int k = 0; k < 6; ++k)
    hexagon.vertices.row(k) << std::cos(k * kPi / 3), std::sin(k * kPi / 3), 0.0;
  hexagon.faces.resize(4, 3);
  hexagon.faces << 0, 2, 4, 0, 1, 2, 2, 3, 4, 4, 5, 0;
  const std::vector<ShellMaterial> materials = mt::varied_materials(4, 29);
  const FittedMidedgeBending fitted = make_term<FittedMidedgeBending>(hexagon, materials);
  const MidedgeBending bisected = make_midedge(hexagon, materials);
  const Vector x = mt::perturbed(hexagon.vertices, 0.2, 30);
  ASSERT_GT(bisected.value(x), 0.0);
  EXPECT_NEAR(fitted.value(x), bisected.value(x), 1e-12 * bisected.value(x));
  // Off the circle (one ear's tip moved out) the fits are unique again and the energies differ.
  TriangleMesh irregular = hexagon;
  irregular.vertices.row(1) *= 1.3;
  const Vector y = mt::perturbed(irregular.vertices, 0.2, 30);
  EXPECT_GT(std::abs(make_term<FittedMidedgeBending>(irregular, materials).value(y) -
                     make_midedge(irregular, materials).value(y)),
            1e-6 * make_midedge(irregular, materials).value(y));
}
