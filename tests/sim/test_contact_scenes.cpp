// Contact scenes: cloth draped on a sphere and on a sharp box (also at 10 m/s and h = 0.04 s),
// tight self-contact by twisting, all intersection-free after every step by CGAL's exact
// predicates; bad input; and the contact effect costing nothing when off.
#include <gtest/gtest.h>

#include <iostream>

#include "common/error.hpp"
#include "sim/contact_scene_support.hpp"

using namespace progsim;
using namespace progsim::contact_scenes;

namespace {

constexpr double kRadius = 0.25;

void report(const char* name, const std::vector<StepRecord>& records) {
  int iterations = 0, converged = 0;
  double min_gap = std::numeric_limits<double>::infinity();
  for (const StepRecord& r : records) {
    iterations += r.newton.iterations;
    converged += r.newton.stop == NewtonStop::converged;
    if (r.contact) min_gap = std::min(min_gap, r.contact->min_gap);
  }
  std::cout << "[ contact ] " << name << ": " << records.size() << " steps, " << converged
            << " converged, " << iterations << " Newton iterations, min gap " << min_gap << " m"
            << std::endl;
}

/// Drops a 0.8 m cloth onto an obstacle whose top is at y = top, and checks that it comes to
/// rest draped over it: the centre rests on the top (above it, nearly still) and the corners
/// hang below it. The hanging flaps may still swing a little (implicit Euler damps them slowly).
void expect_drapes(Scene scene, double top, double centre_speed) {
  LevelSimulation sim(std::move(scene));
  const auto records = run_checked(sim);
  report(sim.scene().name.c_str(), records);
  const Positions p = sim.positions();
  const int n = static_cast<int>(std::lround(std::sqrt(p.rows()))) - 1;
  const int centre = (n / 2) * (n + 1) + n / 2;
  const double speed = sim.velocities().segment<3>(3 * centre).norm();
  std::cout << "[ contact ] centre speed " << speed << " m/s, largest speed " << max_speed(sim)
            << " m/s" << std::endl;
  EXPECT_GT(p(centre, 1), top) << "the cloth's centre went through the obstacle";
  EXPECT_LT(p(0, 1), top - 0.1) << "the corners should hang down";
  EXPECT_LT(speed, centre_speed) << "the centre is not at rest";
}

}  // namespace

TEST(ContactScenes, ClothDrapesOverASphere) {
  Scene scene = cloth_scene(horizontal_cloth(0.8, 14, kRadius + 0.03), 0.3, 0.01, 90);
  scene.name = "cloth_on_sphere";
  scene.obstacles.push_back(static_obstacle("sphere", make_sphere(kRadius, 2), 0.3));
  expect_drapes(std::move(scene), kRadius, 0.02);
}

TEST(ContactScenes, ClothDrapesOverASharpBox) {
  Scene scene = cloth_scene(horizontal_cloth(0.8, 14, 0.23), 0.3, 0.01, 90);
  scene.name = "cloth_on_box";
  scene.obstacles.push_back(static_obstacle("box", make_box(Vec3(0.4, 0.4, 0.4)), 0.3));
  expect_drapes(std::move(scene), 0.2, 0.02);
}

TEST(ContactScenes, FastImpactOnSphereAndBoxWithLargeSteps) {
  // 10 m/s downward, h = 0.04 s: each step moves the cloth 0.4 m, more than the sphere's radius.
  for (int box = 0; box < 2; ++box) {
    SCOPED_TRACE(box ? "box" : "sphere");
    Scene scene = cloth_scene(horizontal_cloth(0.8, 14, kRadius + 0.03), 0.3, 0.04, 20);
    scene.name = box ? "impact_on_box" : "impact_on_sphere";
    scene.bodies[0].velocity = Vec3(0.0, -10.0, 0.0);
    scene.obstacles.push_back(box ? static_obstacle("box", make_box(Vec3(0.5, 0.5, 0.5)), 0.3)
                                  : static_obstacle("sphere", make_sphere(kRadius, 2), 0.3));
    expect_drapes(std::move(scene), box ? 0.25 : kRadius, 0.1);
  }
}

TEST(ContactScenes, ClothTwistedTwoTurnsStaysIntersectionFree) {
  // A 1 m × 0.25 m strip, each end turned 2 full turns the opposite way while the ends close in
  // by 0.2 m: tight self-contact along the whole strip.
  Scene scene;
  scene.name = "twist";
  scene.mode = StepMode::quasistatic;
  scene.time_step = 1.0 / 80.0;
  scene.duration = 1.0;
  scene.gravity.setZero();
  for (Effect e : {Effect::membrane, Effect::bending, Effect::contact}) scene.effects.enable(e);
  scene.bodies.push_back({"strip", make_grid(1.0, 0.25, 24, 6), cloth_material(0.0), 0.0, 0.0});
  scene.contact.dhat = 2e-3;
  const double turns = 2.0, omega = turns * 2.0 * kPi;
  for (int end = 0; end < 2; ++end) {
    Handle h;
    const Positions& v = scene.bodies[0].mesh.vertices;
    for (int i = 0; i < v.rows(); ++i)
      if (std::abs(v(i, 0) - end) < 1e-9) h.vertices.push_back(i);
    h.motion.axis = Vec3::UnitX();
    h.motion.center = Vec3(end, 0.125, 0.0);
    h.motion.angular_velocity = end ? -omega : omega;
    h.motion.velocity = Vec3(end ? -0.1 : 0.1, 0.0, 0.0);
    scene.handles.push_back(h);
  }
  LevelSimulation sim(scene);
  const auto records = run_checked(sim);
  report("twist", records);
  ASSERT_EQ(records.size(), 80u);
  EXPECT_LT(records.back().contact->min_gap, scene.contact.dhat) << "no self-contact happened";
  for (const StepRecord& r : records) EXPECT_EQ(r.script_reached, 1.0) << "step " << r.step;
}

TEST(ContactScenes, SpinningSphereDragsTheClothAroundByFriction) {
  // A cloth lies on a sphere spinning about the vertical axis at 3 rad/s; friction (μ = 0.8)
  // must carry the cloth around with it. The sphere is scripted: it moves in CCD-safe rounds.
  Scene scene = cloth_scene(horizontal_cloth(0.5, 10, kRadius + 0.01), 0.8, 0.01, 60);
  scene.name = "spinning_sphere";
  Obstacle sphere = static_obstacle("sphere", make_sphere(kRadius, 2), 0.8);
  sphere.motion.axis = Vec3::UnitY();
  sphere.motion.angular_velocity = 3.0;
  scene.obstacles.push_back(sphere);
  LevelSimulation sim(scene);
  const Positions start = sim.positions();
  const auto records = run_checked(sim);
  report("spinning_sphere", records);
  // Mean turn about y of the vertices near the top (0.05–0.12 m from the axis).
  double turn = 0.0;
  int counted = 0;
  for (Eigen::Index i = 0; i < start.rows(); ++i) {
    const Vec2 a(start(i, 0), start(i, 2)), b(sim.positions()(i, 0), sim.positions()(i, 2));
    if (a.norm() < 0.05 || a.norm() > 0.12) continue;
    turn += std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    ++counted;
  }
  turn /= counted;
  const double sphere_turn = 3.0 * 0.6;
  std::cout << "[ contact ] cloth turned " << -turn << " rad with the sphere's " << sphere_turn
            << " rad" << std::endl;
  // The sphere turns counter-clockwise about +y, i.e. from +x toward −z: atan2 in the x–z
  // plane measures it as negative.
  EXPECT_GT(-turn, 0.3 * sphere_turn) << "friction did not drag the cloth";
  EXPECT_LT(-turn, 1.05 * sphere_turn);
}

TEST(ContactScenes, IntersectingStartIsRejectedNamingThePair) {
  Scene scene = cloth_scene(horizontal_cloth(0.8, 6, 0.0), 0.0, 0.01, 1);  // through the sphere
  scene.obstacles.push_back(static_obstacle("sphere", make_sphere(kRadius, 1), 0.0));
  try {
    LevelSimulation sim(scene);
    FAIL() << "an intersecting scene was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::intersecting);
    EXPECT_NE(std::string(e.what()).find("face"), std::string::npos) << e.what();
  }
  // Touching within the contact offset (0.25 mm) without intersecting is rejected too.
  Scene touching = cloth_scene(horizontal_cloth(0.8, 6, kRadius + 1e-4), 0.0, 0.01, 1);
  touching.obstacles.push_back(static_obstacle("box", make_box(Vec3(0.5, 0.5, 0.5)), 0.0));
  touching.bodies[0].mesh.vertices.col(1).array() = 0.25 + 1e-4;
  EXPECT_THROW(LevelSimulation{touching}, Error);
}

TEST(ContactScenes, NonsenseContactParametersAreRejected) {
  Scene scene = cloth_scene(horizontal_cloth(0.8, 4, 1.0), 0.0, 0.01, 1);
  Scene bad_dhat = scene;
  bad_dhat.contact.dhat = 0.0;
  EXPECT_THROW(LevelSimulation{bad_dhat}, Error);
  bad_dhat.contact.dhat = -1e-3;
  EXPECT_THROW(LevelSimulation{bad_dhat}, Error);
  Scene bad_mu = scene;
  bad_mu.bodies[0].material.friction = -0.1;
  EXPECT_THROW(LevelSimulation{bad_mu}, Error);
  Scene obstacle_without_contact = scene;
  obstacle_without_contact.effects.disable(Effect::contact);
  obstacle_without_contact.obstacles.push_back(
      static_obstacle("sphere", make_sphere(kRadius, 1), 0.0));
  EXPECT_THROW(LevelSimulation{obstacle_without_contact}, Error);
}

TEST(ContactScenes, DisabledEffectsCostNothing) {
  // Without contact: no contact term, no counters. Contact with μ = 0: no friction term.
  Scene free_fall = cloth_scene(horizontal_cloth(0.8, 4, 1.0), 0.0, 0.01, 2);
  free_fall.effects.disable(Effect::contact);
  LevelSimulation plain(free_fall);
  const StepRecord r = plain.step();
  EXPECT_FALSE(r.contact.has_value());
  EXPECT_EQ(plain.contact(), nullptr);
  for (const TermStats& t : r.terms) EXPECT_NE(t.name, "contact");

  Scene smooth = cloth_scene(horizontal_cloth(0.8, 4, 1.0), 0.0, 0.01, 2);
  smooth.effects.enable(Effect::friction);  // enabled, but every μ is 0
  LevelSimulation frictionless(smooth);
  const StepRecord s = frictionless.step();
  ASSERT_TRUE(s.contact.has_value());
  EXPECT_FALSE(s.friction_contacts.has_value());
  for (const TermStats& t : s.terms) EXPECT_NE(t.name, "friction");
}

TEST(ContactScenes, SymbolicAnalysesAreCountedPerStep) {
  // Issue 33 §2: CHOLMOD's symbolic analysis runs once per Hessian pattern. Without contact the
  // pattern never changes: one analysis in the first step, none after. Falling onto a sphere,
  // the steps count the analyses that contact-set changes cause.
  Scene free_fall = cloth_scene(horizontal_cloth(0.8, 8, 1.0), 0.0, 0.01, 5);
  free_fall.effects.disable(Effect::contact);
  LevelSimulation falling(free_fall);
  EXPECT_EQ(falling.step().newton.symbolic_analyses, 1);
  for (int n = 0; n < 3; ++n) EXPECT_EQ(falling.step().newton.symbolic_analyses, 0);
  Scene scene = cloth_scene(horizontal_cloth(0.8, 8, kRadius + 0.005), 0.0, 0.01, 10);
  scene.obstacles.push_back(static_obstacle("sphere", make_sphere(kRadius, 2), 0.0));
  LevelSimulation draping(scene);
  int analyses = 0, iterations = 0;
  for (int n = 0; n < 10; ++n) {
    const NewtonReport r = draping.step().newton;
    EXPECT_LE(r.symbolic_analyses, r.iterations + 1);
    analyses += r.symbolic_analyses;
    iterations += r.iterations;
  }
  std::cout << "[ contact ] " << analyses << " symbolic analyses in " << iterations
            << " Newton iterations over 10 steps" << std::endl;
  // Issue 33's goal: at most one per step on average (measured: 1 in 38 iterations).
  EXPECT_GE(analyses, 1);
  EXPECT_LE(analyses, 10);
}
