// Handles' reaction forces and partial supports (rollers) against statics: the supports carry
// the weight, their moment balances the weight's, and a propped cantilever's roller carries the
// closed-form 3/8 of the span's load.
#include <gtest/gtest.h>

#include "mesh/mesh_generators.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using progsim::test_support::expect_error;

namespace {

constexpr double kProppedLength = 0.5, kProppedWidth = 0.05, kProppedThickness = 5e-3,
                 kProppedDensity = 1000.0;
constexpr int kProppedCells = 40;
const Vec3 kProppedGravity(0.0, 0.0, -9.81);

/// A stiff strip along x (ν = 0), clamped over its first two columns (x ≤ 1.5 Δx, so the
/// first hinge is held flat); quasistatic, bending under its own weight by about 4 mm.
Scene cantilever_strip_scene() {
  Scene scene;
  scene.name = "strip";
  scene.mode = StepMode::quasistatic;
  scene.time_step = 1.0;
  scene.gravity = kProppedGravity;
  for (Effect e : {Effect::membrane, Effect::bending, Effect::gravity}) scene.effects.enable(e);
  Body body;
  body.name = "strip";
  body.mesh = make_grid(kProppedLength, kProppedWidth, kProppedCells, 2);
  body.material.youngs_modulus = 1e10;
  body.material.poisson_ratio = 0.0;
  body.material.thickness = kProppedThickness;
  body.material.density = kProppedDensity;
  scene.bodies.push_back(body);
  Handle clamp;
  for (int v = 0; v < body.mesh.num_vertices(); ++v)
    if (body.mesh.vertices(v, 0) < 1.5 * kProppedLength / kProppedCells)
      clamp.vertices.push_back(v);
  scene.handles.push_back(clamp);
  scene.solver.tolerance = 1e-8;
  return scene;
}

/// The strip with a second handle on its free end's vertices holding only their height.
Scene propped_strip_scene(unsigned roller_axes) {
  Scene scene = cantilever_strip_scene();
  Handle roller;
  const TriangleMesh& mesh = scene.bodies[0].mesh;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.vertices(v, 0) > kProppedLength - 1e-9) roller.vertices.push_back(v);
  roller.axes = roller_axes;
  scene.handles.push_back(roller);
  return scene;
}

double strip_weight() {
  return kProppedDensity * kProppedThickness * kProppedLength * kProppedWidth *
         -kProppedGravity.z();
}

Vec3 total_reaction_force(const std::vector<HandleReaction>& reactions) {
  Vec3 sum = Vec3::Zero();
  for (const HandleReaction& r : reactions) sum += r.force;
  return sum;
}

}  // namespace

TEST(HandleReactions, TheClampCarriesTheWeightAndItsMoment) {
  LevelSimulation sim(cantilever_strip_scene());
  const StepRecord r = sim.step();
  ASSERT_EQ(r.newton.stop, NewtonStop::converged);
  ASSERT_EQ(r.reactions.size(), 1u);
  const HandleReaction& clamp = r.reactions[0];
  // Statics: the support's force balances the weight ρ h L b g (closed form, not the masses).
  EXPECT_NEAR(clamp.force.z(), strip_weight(), 1e-6 * strip_weight());
  EXPECT_NEAR(clamp.force.x(), 0.0, 1e-6 * strip_weight());
  EXPECT_NEAR(clamp.force.y(), 0.0, 1e-6 * strip_weight());
  // ... and its moment about its centroid balances the weight's moment, Σ (x_i − c) × m_i g.
  Vec3 weight_moment = Vec3::Zero();
  const auto x = sim.positions();
  for (int v = 0; v < x.rows(); ++v)
    weight_moment +=
        (x.row(v).transpose() - clamp.point).cross(sim.model().vertex_masses[v] * kProppedGravity);
  EXPECT_LT((clamp.moment + weight_moment).norm(), 1e-6 * weight_moment.norm());
  // A cantilever of length L under q: the clamp moment q L²/2 about y, to the clamp's width.
  const double span =
      kProppedLength - 0.75 * kProppedLength / kProppedCells;  // from the clamp's centroid
  EXPECT_NEAR(clamp.moment.y(), -strip_weight() / kProppedLength * span * span / 2.0,
              0.03 * strip_weight() * span);
}

TEST(HandleReactions, APropCarriesThreeEighthsOfTheSpanAndARollerNoHorizontalLoad) {
  LevelSimulation sim(propped_strip_scene(handle_axis_z));
  const StepRecord r = sim.step();
  ASSERT_EQ(r.newton.stop, NewtonStop::converged);
  ASSERT_EQ(r.reactions.size(), 2u);
  EXPECT_LT((total_reaction_force(r.reactions) - Vec3(0, 0, strip_weight())).norm(),
            1e-6 * strip_weight());
  // Propped cantilever under a uniform load q (beam theory): the prop carries 3 q ℓ / 8 of the
  // span ℓ between the held hinge (x = Δx) and the prop, plus its own half cell's weight.
  const double dx = kProppedLength / kProppedCells, q = strip_weight() / kProppedLength,
               span = kProppedLength - dx;
  const double prop = 3.0 * q * span / 8.0 + q * dx / 2.0;
  EXPECT_NEAR(r.reactions[1].force.z(), prop, 0.03 * prop);
  // The roller is free in x and y: nothing pushes along the strip, and its end slid inward as
  // the strip sagged (by about w²/ℓ).
  EXPECT_EQ(r.reactions[1].force.x(), 0.0);
  EXPECT_LT(std::abs(r.reactions[0].force.x()), 1e-6 * strip_weight());
  const TriangleMesh& rest = sim.scene().bodies[0].mesh;
  const int end = kProppedCells;  // vertex (i = nx, j = 0)
  EXPECT_LT(sim.positions()(end, 0), rest.vertices(end, 0) - 1e-7);
  EXPECT_EQ(sim.positions()(end, 2), rest.vertices(end, 2));  // held in height

  // Negative control: a pin instead of the roller stretches the sagging strip, and the clamp
  // pulls on it horizontally with a force of the order of the weight or more.
  LevelSimulation pinned(propped_strip_scene(handle_axes_all));
  const StepRecord p = pinned.step();
  ASSERT_EQ(p.newton.stop, NewtonStop::converged);
  EXPECT_GT(std::abs(p.reactions[0].force.x()), 0.1 * strip_weight());
  EXPECT_EQ(pinned.positions()(end, 0), rest.vertices(end, 0));
}

TEST(HandleReactions, ARollerHoldsOnEveryLevelOfAProgressiveSolve) {
  Scene scene = propped_strip_scene(handle_axis_z);
  scene.progressive.coarse_levels = 1;
  ProgressiveSimulation psq(scene);
  psq.step();
  EXPECT_TRUE(psq.records()[0].reactions.empty());  // a preview reports none
  psq.refine();
  ASSERT_TRUE(psq.settle_to_equilibrium(20));
  const std::vector<HandleReaction>& finest = psq.records()[psq.finest()].reactions;
  ASSERT_EQ(finest.size(), 2u);
  EXPECT_LT((total_reaction_force(finest) - Vec3(0, 0, strip_weight())).norm(),
            1e-6 * strip_weight());
  const TriangleMesh& rest = scene.bodies[0].mesh;
  EXPECT_LT(psq.current().positions()(kProppedCells, 0), rest.vertices(kProppedCells, 0) - 1e-7);
}

TEST(HandleReactions, DirectDynamicStepsReportTheForceThatAcceleratesTheHandle) {
  // A handle dragging a strip sideways at constant velocity from rest: in the first step the
  // handle and the strip accelerate to v, so Σ R = Σ m a − Σ m g over the whole strip
  // (Newton's second law; the elastic forces cancel in the sum).
  Scene scene = cantilever_strip_scene();
  scene.mode = StepMode::dynamic;
  scene.time_step = 1e-3;
  scene.handles[0].motion.velocity = Vec3(0.0, 0.2, 0.0);
  scene.solver.tolerance = 1e-6;
  LevelSimulation sim(scene);
  const Vector before = sim.dofs();
  const StepRecord r = sim.step();
  ASSERT_EQ(r.newton.stop, NewtonStop::converged);
  const Eigen::VectorXd& m = sim.model().vertex_masses;
  Vec3 momentum_change = Vec3::Zero();
  for (int v = 0; v < m.size(); ++v)
    momentum_change += m[v] * (sim.dofs().segment<3>(3 * v) - before.segment<3>(3 * v)) /
                       (scene.time_step * scene.time_step);  // m (x¹ − x⁰)/h², v⁰ = 0
  const Vec3 expected = momentum_change - m.sum() * kProppedGravity;
  EXPECT_LT((r.reactions[0].force - expected).norm(), 1e-6 * expected.norm());
  EXPECT_GT(r.reactions[0].force.y(), 0.0);
}

TEST(HandleReactions, AxesAreParsedAndChecked) {
  const std::string scene = R"({
    "simulation": {"mode": "quasistatic"},
    "effects": ["membrane"],
    "bodies": [{"mesh": {"generator": "grid", "width": 1, "height": 1, "nx": 2, "ny": 2}}],
    "handles": [{"body": 0, "vertices": [0, 1], "axes": AXES}]
  })";
  const auto with = [&](const std::string& axes) {
    std::string text = scene;
    text.replace(text.find("AXES"), 4, axes);
    return text;
  };
  EXPECT_EQ(parse_scene(with(R"("xz")"), ".").handles[0].axes, handle_axis_x | handle_axis_z);
  EXPECT_EQ(parse_scene(with(R"("zyx")"), ".").handles[0].axes, unsigned{handle_axes_all});
  for (const char* bad : {R"("")", R"("xx")", R"("w")", "3"})
    expect_error([&] { parse_scene(with(bad), "."); }, Status::invalid_scene, {"handles[0].axes"});
  Scene code = parse_scene(with(R"("y")"), ".");
  code.handles[0].axes = 8;
  expect_error([&] { validate_scene(code); }, Status::invalid_scene, {"handles[0]", "axes"});
}
