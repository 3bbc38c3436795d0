// Volumetric Progressive Dynamics over non-nested tet boxes: momentum of a spinning free jelly
// on every level (PD-VPD-NOTES risk 7), a drop on the ground that every level animates alike,
// without crossing the ground or inverting a tet, and misuse.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <iostream>
#include <memory>
#include <string>

#include "common/error.hpp"
#include "hierarchy/tet_prolongation.hpp"
#include "mesh/intersection_check.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_generators.hpp"
#include "progressive/volumetric_dynamics.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using progsim::test_support::expect_error;

namespace {

const Vec3 kSize(0.2, 0.2, 0.2);

/// The levels `meshes` bound by W.
std::shared_ptr<const TetHierarchy> bound_levels(std::vector<TetMesh> meshes) {
  auto h = std::make_shared<TetHierarchy>();
  h->levels = std::move(meshes);
  for (std::size_t l = 0; l + 1 < h->levels.size(); ++l) {
    h->bindings.push_back(bind_to_tets(h->levels[l], h->levels[l + 1]));
    h->to_finer.push_back(tet_prolongation_matrix(h->bindings.back(), h->levels[l]));
  }
  return h;
}

/// Boxes of 2³, 3³ and 5³ cells (their vertices do not nest), moved by `shift`, bound by W.
std::shared_ptr<const TetHierarchy> box_levels(const Vec3& shift) {
  std::vector<TetMesh> meshes;
  for (int n : {2, 3, 5}) {
    meshes.push_back(make_tet_box(kSize, n, n, n));
    meshes.back().vertices.rowwise() += shift.transpose();
  }
  return bound_levels(std::move(meshes));
}

Scene jelly_scene(const TetMesh& finest, double duration) {
  Scene s;
  s.name = "jelly";
  s.mode = StepMode::dynamic;
  s.time_step = 0.01;
  s.duration = duration;
  s.gravity = Vec3(0.0, -9.81, 0.0);
  s.effects.enable(Effect::elasticity);
  Body b;
  b.name = "jelly";
  b.mesh.vertices = finest.vertices;
  b.mesh.faces = tet_boundary_faces(finest);
  b.tets = finest.tets;
  b.material.youngs_modulus = 2e4;
  b.material.poisson_ratio = 0.4;
  b.material.density = 1000.0;
  b.material.friction = 0.5;
  s.bodies.push_back(b);
  return s;
}

Vec3 center_of_mass_velocity(const DynamicStepRecord& r, const Vec3& previous, double h) {
  return (r.motion.center_of_mass - previous) / h;
}

double min_tet_determinant(const TetMesh& mesh, const Positions& x) {
  double lowest = INFINITY;
  for (int t = 0; t < mesh.num_tets(); ++t) {
    Mat3 d;
    for (int k = 0; k < 3; ++k)
      d.col(k) = (x.row(mesh.tets(t, k + 1)) - x.row(mesh.tets(t, 0))).transpose();
    lowest = std::min(lowest, d.determinant());
  }
  return lowest;
}

}  // namespace

TEST(VolumetricDynamics, ASpinningFreeJellyKeepsItsMomentumOnEveryLevel) {
  const auto levels = box_levels(Vec3::Zero());
  Scene scene = jelly_scene(levels->levels.back(), 0.2);
  // jelly_scene enables no gravity: free flight
  VolumetricDynamics vpd(scene, levels);
  const Vec3 v0(0.3, -0.2, 0.1), omega(0.0, 6.0, 2.0);
  const Positions& rest = levels->levels[0].vertices;  // centred at the origin, its CoM
  Positions v(rest.rows(), 3);
  for (int i = 0; i < rest.rows(); ++i)
    v.row(i) = (v0 + omega.cross(rest.row(i).transpose())).transpose();
  vpd.set_preview_velocities(as_dofs(v));
  for (int t = 0; t < 20; ++t) vpd.step_preview();
  vpd.refine();
  vpd.refine();
  for (int level = 0; level <= vpd.finest(); ++level) {
    const DynamicLevelRecord& r = vpd.record(level);
    ASSERT_EQ(r.steps.size(), 20u);
    Vec3 previous = r.start_center_of_mass;
    for (const DynamicStepRecord& step : r.steps) {
      const Vec3 velocity = center_of_mass_velocity(step, previous, 0.01);
      EXPECT_LT((velocity - v0).norm(), 1e-6 * v0.norm())
          << "level " << level << " step " << step.step;
      previous = step.motion.center_of_mass;
    }
  }
}

TEST(VolumetricDynamics, EveryLevelLandsAsThePreviewDidAboveTheGroundWithTetsPositive) {
  const Mat3 tilt = Eigen::AngleAxisd(0.4, Vec3(1, 0, 1).normalized()).toRotationMatrix();
  auto levels = std::make_shared<TetHierarchy>(*box_levels(Vec3::Zero()));
  for (TetMesh& m : levels->levels) {
    m.vertices = m.vertices * tilt.transpose();
    m.vertices.col(1).array() += 0.2;
  }
  Scene scene = jelly_scene(levels->levels.back(), 0.5);
  scene.effects.enable(Effect::gravity);
  scene.effects.enable(Effect::contact);
  scene.effects.enable(Effect::friction);
  scene.ground.enabled = true;
  scene.ground.friction = 0.5;
  scene.contact.dhat = 1e-3;
  VolumetricDynamics vpd(scene, levels);
  for (int t = 0; t < 50; ++t) vpd.step_preview();
  vpd.refine();
  vpd.refine();
  Positions x, v;
  for (int level = 0; level <= vpd.finest(); ++level)
    for (int frame = 0; frame < vpd.num_frames(level); ++frame) {
      vpd.read_frame(level, frame, x, v);
      ASSERT_GT(x.col(1).minCoeff(), 0.0) << "level " << level << " frame " << frame;
      ASSERT_GT(min_tet_determinant(levels->levels[level], x), 0.0);
      // the boundary by CGAL's exact predicates: no two faces intersect
      ASSERT_TRUE(intersecting_faces(x, vpd.surface_faces(level), 1).empty())
          << "level " << level << " frame " << frame;
    }
  const double preview_drop =
      vpd.record(0).start_center_of_mass.y() - vpd.record(0).steps.back().motion.center_of_mass.y();
  EXPECT_GT(preview_drop, 0.05);  // it fell and landed
  for (int level = 1; level <= vpd.finest(); ++level) {
    const DynamicLevelRecord& r = vpd.record(level);
    EXPECT_EQ(r.converged_steps, 50) << "level " << level;
    EXPECT_LT(r.steps.back().com_deviation, 0.1 * kSize.x()) << "level " << level;
    std::cout << "jelly level " << level << ": final CoM deviation from the preview "
              << r.steps.back().com_deviation << " m, consistency " << r.steps.back().consistency
              << " m\n";
  }
}

TEST(VolumetricDynamics, MisuseIsRefusedNamingIt) {
  const auto levels = box_levels(Vec3::Zero());
  Scene scene = jelly_scene(levels->levels.back(), 0.1);
  VolumetricDynamics vpd(scene, levels);
  EXPECT_THROW(vpd.refine(), Error);  // nothing previewed
  vpd.step_preview();
  vpd.refine();
  EXPECT_THROW(vpd.step_preview(), Error);  // refined from it
  EXPECT_THROW(vpd.record(2), Error);
  Scene quasistatic = scene;
  quasistatic.mode = StepMode::quasistatic;
  EXPECT_THROW(VolumetricDynamics(quasistatic, levels), Error);
  Scene other = jelly_scene(levels->levels[0], 0.1);  // the body is not the finest level
  expect_error([&] { VolumetricDynamics(other, levels); }, Status::invalid_argument, {});
  Scene per_frame = scene;  // restarting each step from the coarse frame: no safe tet refinement
  per_frame.effects.enable(Effect::contact);
  per_frame.ground.enabled = true;
  per_frame.ground.height = -1.0;
  per_frame.progressive.prediction = DynamicsPrediction::per_frame;
  VolumetricDynamics restarted(per_frame, levels);
  restarted.step_preview();
  expect_error([&] { restarted.refine(); }, Status::unsupported, {"per_frame"});
  Scene grounded = scene;  // a later window starts from a coarse frame refined vertically
  grounded.effects.enable(Effect::contact);
  grounded.ground.enabled = true;
  grounded.ground.height = -1.0;
  VolumetricDynamics windowed(grounded, levels);
  windowed.step_preview();
  windowed.step_preview();
  expect_error([&] { windowed.refine_window({1, 2}); }, Status::unsupported,
               {"window starting after frame 0", "tets"});
  EXPECT_EQ(windowed.level(), 0);
  windowed.refine_window({0, 1});  // from frame 0 no vertical refinement is needed
  EXPECT_EQ(windowed.num_frames(1), 2);
  EXPECT_EQ(restarted.level(), 0);
  Scene handled = scene;
  Handle listed;  // by index: no counterpart on the coarse levels
  listed.vertices = {0};
  handled.handles.push_back(listed);
  expect_error([&] { VolumetricDynamics(handled, levels); }, Status::unsupported, {});
}

TEST(VolumetricDynamics, AHandleBoxClampsItsVerticesOnEveryLevel) {
  // A 0.4 m bar centred at the origin, of 4, 8 and 12 cells along x (vertices at its ends on
  // every level, elsewhere not nested), clamped at x = −0.2 by a box, sagging under gravity.
  const Vec3 bar(0.4, 0.1, 0.1);
  const auto levels = bound_levels(
      {make_tet_box(bar, 4, 1, 1), make_tet_box(bar, 8, 2, 2), make_tet_box(bar, 12, 3, 3)});
  Scene scene = jelly_scene(levels->levels.back(), 0.1);
  scene.effects.enable(Effect::gravity);
  scene.bodies[0].material.youngs_modulus = 1e5;
  Handle clamp;
  clamp.region = VertexBox{Vec3(-0.2 - 1e-9, -1.0, -1.0), Vec3(-0.2 + 1e-9, 1.0, 1.0)};
  clamp.vertices = clamp.region->select(scene.bodies[0].mesh.vertices);
  scene.handles.push_back(clamp);
  VolumetricDynamics vpd(scene, levels);
  for (int t = 0; t < 10; ++t) vpd.step_preview();
  vpd.refine();
  vpd.refine();
  const int face_vertices[] = {2 * 2, 3 * 3, 4 * 4};
  Positions x, v;
  for (int level = 0; level <= vpd.finest(); ++level) {
    const TetMesh& mesh = levels->levels[level];
    const std::vector<int> held = vpd.level_scene(level).handles[0].vertices;
    ASSERT_EQ(static_cast<int>(held.size()), face_vertices[level]) << "level " << level;
    for (int frame = 0; frame < vpd.num_frames(level); ++frame) {
      vpd.read_frame(level, frame, x, v);
      for (int i : held)
        ASSERT_EQ((x.row(i) - mesh.vertices.row(i)).norm(), 0.0) << "level " << level;
    }
    // the free end (x = 0.2) sags along gravity (−y)
    double tip_drop = 0.0;
    for (int i = 0; i < mesh.num_vertices(); ++i)
      if (mesh.vertices(i, 0) > bar.x() / 2 - 1e-9)
        tip_drop = std::max(tip_drop, mesh.vertices(i, 1) - x(i, 1));
    EXPECT_GT(tip_drop, 1e-3) << "level " << level;
    EXPECT_EQ(vpd.record(level).converged_steps, 10) << "level " << level;
  }
  // A box holding finest vertices (x = −0.133) but none of level 0's (x = −0.2, −0.1, …) nor
  // level 1's (−0.15, −0.1, …) is refused, naming the coarsest.
  Scene gap = scene;
  gap.handles[0].region = VertexBox{Vec3(-0.14, -1.0, -1.0), Vec3(-0.13, 1.0, 1.0)};
  gap.handles[0].vertices = gap.handles[0].region->select(scene.bodies[0].mesh.vertices);
  ASSERT_FALSE(gap.handles[0].vertices.empty());
  expect_error([&] { VolumetricDynamics(gap, levels); }, Status::invalid_scene,
               {"handles[0].box holds no vertex of tet level 0"});
}
