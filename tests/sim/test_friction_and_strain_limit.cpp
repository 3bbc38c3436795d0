// Friction physics on an incline (stick when tan θ < μ, slide with a = g(sin θ − μ cos θ)
// otherwise) and strain limiting (a heavy hanging cloth never stretches past its limit).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>

#include "common/constants.hpp"
#include "energy/strain_limit.hpp"
#include "sim/contact_scene_support.hpp"

using namespace progsim;
using namespace progsim::contact_scenes;

namespace {

constexpr double kGravity = 9.81;

struct Incline {
  Vec3 normal;    ///< of the slope
  Vec3 downhill;  ///< unit, in the slope
};

Incline incline(double theta) {
  return {Vec3(-std::sin(theta), std::cos(theta), 0.0),
          -Vec3(std::cos(theta), std::sin(theta), 0.0)};
}

/// A stiff 10 cm square plate lying on a slope of angle θ (ground through the origin), hovering
/// half a contact gap above it, with μ on both surfaces.
Scene plate_on_incline(double theta, double mu, int steps) {
  const Incline slope = incline(theta);
  TriangleMesh plate = make_grid(0.1, 0.1, 4, 4);
  const Eigen::AngleAxisd lay_flat(-0.5 * kPi, Vec3::UnitX());
  const Eigen::AngleAxisd tilt(theta, Vec3::UnitZ());
  ShellMaterial m;
  m.youngs_modulus = 1e8;
  m.thickness = 1e-3;
  m.density = 1000;
  m.friction = mu;
  Scene scene;
  scene.name = "incline";
  scene.time_step = 0.01;
  scene.duration = steps * scene.time_step;
  scene.contact.dhat = 1e-3;
  const double lift = 0.5 * m.thickness + 0.5 * scene.contact.dhat;
  for (Eigen::Index i = 0; i < plate.vertices.rows(); ++i)
    plate.vertices.row(i) =
        (tilt * (lay_flat * plate.vertices.row(i).transpose()) + lift * slope.normal).transpose();
  for (Effect e :
       {Effect::membrane, Effect::bending, Effect::gravity, Effect::contact, Effect::friction})
    scene.effects.enable(e);
  scene.bodies.push_back({"plate", plate, m, 0.0, 0.0});
  scene.ground = Ground{true, slope.normal, 0.0, mu};
  return scene;
}

/// Mean velocity of the plate along the slope (m/s).
double downhill_speed(const LevelSimulation& sim, const Vec3& downhill) {
  return (as_positions(sim.velocities()) * downhill).mean();
}

/// A free 1 m square cloth (8 × 8 cells, strain limit 1.1), quasistatic over one step, whose
/// column of vertices `column` (0: left edge, 8: right edge) moves `dx` metres along x.
Scene edge_pulled_sheet(double dx, int column) {
  Scene scene;
  scene.name = "edge_pulled";
  scene.mode = StepMode::quasistatic;
  scene.time_step = 1.0;
  scene.duration = 1.0;
  for (Effect e : {Effect::membrane, Effect::bending, Effect::strain_limit})
    scene.effects.enable(e);
  ShellMaterial m = cloth_material(0.0);
  m.strain_limit = 1.1;
  scene.bodies.push_back({"cloth", make_grid(1.0, 1.0, 8, 8), m, 0.0, 0.0});
  Handle edge;
  for (int j = 0; j <= 8; ++j) edge.vertices.push_back(9 * j + column);
  edge.motion.velocity = Vec3(dx, 0.0, 0.0);
  scene.handles.push_back(edge);
  return scene;
}

}  // namespace

TEST(Friction, PlateSlidesDownAnInclineWithCoulombAcceleration) {
  const double theta = 30.0 * kPi / 180.0, mu = 0.3;
  LevelSimulation sim(plate_on_incline(theta, mu, 60));
  const Vec3 downhill = incline(theta).downhill;
  double v20 = 0.0;
  for (int s = 1; s <= 60; ++s) {
    sim.step();
    if (s == 20) v20 = downhill_speed(sim, downhill);
  }
  const double measured = (downhill_speed(sim, downhill) - v20) / (40 * 0.01);
  const double expected = kGravity * (std::sin(theta) - mu * std::cos(theta));
  std::cout << "[ friction ] sliding acceleration " << measured << " m/s², Coulomb " << expected
            << " m/s²" << std::endl;
  EXPECT_NEAR(measured, expected, 0.05 * expected);
}

TEST(Friction, PlateSticksWhenTheSlopeIsBelowTheFrictionAngle) {
  const double theta = 30.0 * kPi / 180.0, mu = 0.7;  // tan θ = 0.577 < μ
  Scene scene = plate_on_incline(theta, mu, 60);
  LevelSimulation sim(scene);
  for (int s = 0; s < 10; ++s) sim.step();  // settles onto the slope
  const Positions start = sim.positions();
  for (int s = 10; s < 60; ++s) sim.step();
  const double slid = ((sim.positions() - start) * incline(theta).downhill).mean();
  // Smoothed static friction creeps below ε_v = 1 mm/s: at most 0.5 mm in 0.5 s. A free slide
  // would cover ½ g sin θ t² ≈ 0.6 m, a Coulomb slide with μ = 0.3 still 0.3 m.
  std::cout << "[ friction ] sticking plate moved " << slid << " m in 0.5 s" << std::endl;
  EXPECT_LT(std::abs(slid), scene.contact.friction_velocity * 0.5);
}

TEST(Friction, TheFirstSolveOfANewSimulationFreezesItsContacts) {
  // A settle() before any step (a refined level's first solve) must lag friction too: without
  // it the plate would solve frictionless and slide.
  LevelSimulation sim(plate_on_incline(0.1, 0.5, 1));
  const StepRecord settled = sim.settle();
  ASSERT_TRUE(settled.friction_contacts.has_value());
  EXPECT_GT(*settled.friction_contacts, 0);
}

TEST(StrainLimit, HeavyHangingClothNeverExceedsItsLimit) {
  // A heavy cloth hanging from two corners stretches over 10% without a limit; with s_max = 1.06
  // its largest principal stretch must stay below 1.06 (1 + 1e-3) at every step.
  auto hanging = [](bool limited) {
    Scene scene;
    scene.name = "strain_limit";
    scene.time_step = 0.02;
    scene.duration = 0.6;
    for (Effect e : {Effect::membrane, Effect::bending, Effect::gravity}) scene.effects.enable(e);
    if (limited) scene.effects.enable(Effect::strain_limit);
    ShellMaterial m = cloth_material(0.0);
    m.youngs_modulus = 2e5;
    m.density = 2000;
    m.strain_limit = 1.06;
    scene.bodies.push_back({"cloth", make_grid(1.0, 1.0, 12, 12), m, 0.0, 0.0});
    scene.gravity = Vec3(0.0, -9.81, 0.0);
    Handle corners;
    corners.vertices = {12 * 13, 12 * 13 + 12};
    scene.handles.push_back(corners);
    return scene;
  };
  LevelSimulation free(hanging(false));
  const TriangleMesh& mesh = free.model().rest;
  const StrainLimit gauge(mesh.vertices, mesh.faces, std::vector<double>(mesh.num_faces(), 1.06),
                          0.03, 1.0);
  double free_max = 0.0;
  for (int s = 0; s < free.scene().num_steps(); ++s) {
    free.step();
    free_max = std::max(free_max, gauge.max_stretch(free.dofs()));
  }
  std::cout << "[ strain limit ] without the limit the cloth stretches to " << free_max
            << std::endl;
  ASSERT_GT(free_max, 1.1) << "the scene must stretch past the limit without it";
  LevelSimulation limited(hanging(true));
  double limited_max = 0.0;
  for (int s = 0; s < limited.scene().num_steps(); ++s) {
    const StepRecord r = limited.step();
    ASSERT_TRUE(r.max_stretch.has_value());
    limited_max = std::max(limited_max, *r.max_stretch);
    EXPECT_LE(*r.max_stretch, 1.06 * (1.0 + 1e-3)) << "step " << r.step;
    EXPECT_TRUE(limited.dofs().allFinite());
  }
  std::cout << "[ strain limit ] largest stretch " << limited_max << " (limit 1.06)" << std::endl;
}

TEST(StrainLimit, AStretchNoStateCanMeetIsNeverCalledAnEquilibrium) {
  // Both side edges of a square cloth held, the right one pulled 0.2 m out in one quasistatic
  // step: every row between them must stretch by at least 1.2 on average, past the limit 1.1.
  // The raised limits cannot come down, so no solve may report an equilibrium.
  Scene scene = edge_pulled_sheet(0.2, 8);
  Handle left;
  for (int j = 0; j <= 8; ++j) left.vertices.push_back(9 * j);
  scene.handles.push_back(left);
  LevelSimulation sim(scene);
  StepRecord r = sim.step();
  for (int k = 0; k < 20; ++k) {
    EXPECT_GT(r.raised_limits, 0) << "solve " << k;
    EXPECT_FALSE(r.equilibrium) << "solve " << k;
    r = sim.settle();
  }
  EXPECT_TRUE(sim.dofs().allFinite());
}

TEST(StrainLimit, AHandleMovedBeyondTheLimitIsFollowedNotRefused) {
  // The left edge of a free square cloth jumps 0.2 m to the left in one quasistatic step: at
  // the step's start the first column of faces (0.125 m wide) is stretched to σ₁ ≈ 2.6, past
  // the limit 1.1, where the barrier is infinite. The limits are raised for the solve and come
  // back down as the cloth follows the edge.
  Scene scene = edge_pulled_sheet(-0.2, 0);
  LevelSimulation sim(scene);
  StepRecord r = sim.step();
  EXPECT_NE(r.newton.stop, NewtonStop::non_finite);
  EXPECT_GT(r.raised_limits, 0);  // some faces start beyond the limit
  for (int k = 0; k < 50 && r.raised_limits > 0; ++k) r = sim.settle();
  EXPECT_EQ(r.raised_limits, 0);
  ASSERT_TRUE(r.max_stretch.has_value());
  EXPECT_LT(*r.max_stretch, 1.1);
  EXPECT_NEAR(sim.dofs()[0], -0.2, 1e-9);  // the handle is where its script puts it
  EXPECT_TRUE(sim.dofs().allFinite());
}
