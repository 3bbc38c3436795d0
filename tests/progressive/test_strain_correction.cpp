// Strain-limit correction of a refined start (PSQ §4.4.5): a tent pulled out of a sheet comes
// under its strain limit with the held vertices untouched (stretches checked with Eigen's SVD,
// not the term's spectrum); faces whose vertices are all held stay as they are and are
// counted; an obstacle inside the tent stops the correction short of the limit, intersection-
// free by CGAL's exact predicates, and the faces it leaves over are counted.
#include <gtest/gtest.h>

#include <vector>

#include "contact/collision_mesh.hpp"
#include "contact/contact_potential.hpp"
#include "mesh/intersection_check.hpp"
#include "mesh/mesh_generators.hpp"
#include "progressive/strain_correction.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;

namespace strain_correction_test {
namespace {

constexpr double kLimit = 1.1;
constexpr int kCells = 4;  // 5 × 5 vertices, edge 0.25 m
constexpr int kCentre = 12;

/// A 1 m square sheet with strain limit kLimit on every face.
ShellModel sheet() {
  ShellModel model;
  model.rest = make_grid(1.0, 1.0, kCells, kCells);
  ShellMaterial material;
  material.strain_limit = kLimit;
  model.face_materials.assign(model.rest.num_faces(), material);
  model.vertex_offset = {0, model.rest.num_vertices()};
  model.face_offset = {0, model.rest.num_faces()};
  model.vertex_masses = Eigen::VectorXd::Ones(model.rest.num_vertices());
  return model;
}

/// The sheet with its centre vertex lifted by `height` (a tent).
Vector tent(const ShellModel& model, double height) {
  Vector x = as_dofs(model.rest.vertices);
  x[3 * kCentre + 2] = height;
  return x;
}

/// Every vertex held but `free_vertices`.
std::vector<bool> held_except(const ShellModel& model, const std::vector<int>& free_vertices) {
  std::vector<bool> fixed(3 * model.rest.num_vertices(), true);
  for (int v : free_vertices)
    for (int d = 0; d < 3; ++d) fixed[3 * v + d] = false;
  return fixed;
}

double max_stretch(const ShellModel& model, const Vector& x) {
  return progsim::test_support::max_membrane_stretch(model.rest.vertices, model.rest.faces, x);
}

/// The interior vertices of the sheet (the boundary held).
std::vector<int> interior() {
  std::vector<int> out;
  for (int j = 1; j < kCells; ++j)
    for (int i = 1; i < kCells; ++i) out.push_back(j * (kCells + 1) + i);
  return out;
}

/// A small horizontal triangle at height z under the tent's apex.
struct Obstacle {
  Positions vertices{3, 3};
  Faces faces{1, 3};
  explicit Obstacle(double z) {
    vertices << 0.47, 0.47, z, 0.53, 0.47, z, 0.5, 0.53, z;
    faces << 0, 1, 2;
  }
};

/// The contact barrier between the sheet and the obstacle.
std::unique_ptr<ContactPotential> contact_with(const ShellModel& model, const Obstacle& o) {
  const int n = model.rest.num_vertices();
  CollisionMesh mesh =
      build_collision_mesh(model.rest.vertices, model.rest.faces, std::vector<double>(n, 0.0),
                           std::vector<double>(n, 0.0), {{&o.vertices, &o.faces, 0.0}});
  auto contact = std::make_unique<ContactPotential>(std::move(mesh), 1e-3, 1.0, std::nullopt);
  contact->set_obstacle_positions(o.vertices);
  return contact;
}

}  // namespace

TEST(StrainCorrection, ATentComesUnderItsLimitWithTheHeldVerticesUntouched) {
  const ShellModel model = sheet();
  const Vector start = tent(model, 0.3);
  ASSERT_GT(max_stretch(model, start), 1.5);
  Vector x = start;
  const std::vector<bool> fixed = held_except(model, interior());
  const StrainCorrectionStats stats = correct_strain(model, fixed, nullptr, 1.0, x);
  EXPECT_GT(stats.strained_faces, 0);
  EXPECT_EQ(stats.over_limit_faces, 0);
  EXPECT_GT(stats.newton_iterations, 0);
  EXPECT_NEAR(stats.stretch_before, max_stretch(model, start), 1e-9);
  EXPECT_NEAR(stats.stretch_after, max_stretch(model, x), 1e-9);
  EXPECT_LT(max_stretch(model, x), kLimit);
  for (int d = 0; d < x.size(); ++d)
    if (fixed[d]) EXPECT_EQ(x[d], start[d]) << "held DOF " << d << " moved";
}

TEST(StrainCorrection, LeavesAStateUnderItsLimitsAndFacesItCannotMoveUnchanged) {
  const ShellModel model = sheet();
  Vector x = tent(model, 0.02);  // stretch 1.003: under the limit
  const Vector start = x;
  StrainCorrectionStats stats =
      correct_strain(model, held_except(model, interior()), nullptr, 1.0, x);
  EXPECT_EQ(stats.strained_faces, 0);
  EXPECT_EQ(stats.newton_iterations, 0);
  EXPECT_EQ(x, start);
  // Every vertex held: the tent's faces are beyond their limit and stay so, counted.
  x = tent(model, 0.3);
  const Vector lifted = x;
  stats = correct_strain(model, held_except(model, {}), nullptr, 1.0, x);
  EXPECT_GT(stats.strained_faces, 0);
  EXPECT_EQ(stats.over_limit_faces, stats.strained_faces);
  EXPECT_EQ(x, lifted);
  // Without a strain-limited face there is nothing to do.
  ShellModel unlimited = sheet();
  for (ShellMaterial& m : unlimited.face_materials) m.strain_limit = 0.0;
  stats = correct_strain(unlimited, held_except(unlimited, interior()), nullptr, 1.0, x);
  EXPECT_EQ(stats.strained_faces, 0);
  EXPECT_EQ(stats.stretch_before, 0.0);
  EXPECT_EQ(x, lifted);
}

TEST(StrainCorrection, AnObstacleInsideTheTentStopsItIntersectionFreeAndTheRestIsCounted) {
  const ShellModel model = sheet();
  const Obstacle obstacle(0.15);
  // Only the apex moves. Without the obstacle it comes under the limit below its height.
  Vector free_apex = tent(model, 0.3);
  const StrainCorrectionStats alone =
      correct_strain(model, held_except(model, {kCentre}), nullptr, 1.0, free_apex);
  EXPECT_EQ(alone.over_limit_faces, 0);
  EXPECT_LT(free_apex[3 * kCentre + 2], 0.15);
  Vector x = tent(model, 0.3);
  const StrainCorrectionStats stats =
      correct_strain(model, held_except(model, {kCentre}), contact_with(model, obstacle), 1.0, x);
  EXPECT_GT(stats.strained_faces, 0);
  EXPECT_GT(stats.over_limit_faces, 0);  // the limit is out of reach above the obstacle
  EXPECT_LT(stats.stretch_after, stats.stretch_before);
  EXPECT_GT(x[3 * kCentre + 2], 0.15);
  // CGAL's exact predicates: the sheet and the obstacle do not cross.
  Positions all(model.rest.num_vertices() + 3, 3);
  all << as_positions(x), obstacle.vertices;
  Faces faces(model.rest.num_faces() + 1, 3);
  faces << model.rest.faces, obstacle.faces.array() + model.rest.num_vertices();
  EXPECT_TRUE(intersecting_faces(all, faces).empty());
}

}  // namespace strain_correction_test
