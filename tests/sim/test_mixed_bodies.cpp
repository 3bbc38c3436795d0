// Scenes that mix shells and volumetric (tet) bodies, simulated directly: a steel plate resting
// on a jelly column compresses it as the Neo-Hookean closed form says, and the bundled cloth
// dropped on a jelly cube stays intersection-free with every tet positive.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "common/error.hpp"
#include "contact_scene_support.hpp"
#include "energy/midedge_bending.hpp"
#include "mesh/mesh_generators.hpp"
#include "progressive/progressive_animation.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "scene/scene_parameters.hpp"
#include "sim/level_simulation.hpp"
#include "sim/shell_elastics.hpp"
#include "support/solid_box.hpp"

using namespace progsim;
using namespace progsim::contact_scenes;

namespace mixed_bodies {  // named: the unity build shares anonymous namespaces between files

constexpr double kG = 9.81;
constexpr double kColumn = 0.2;                                // jelly column: kColumn³, m
constexpr double kJellyModulus = 1e5, kJellyDensity = 1000.0;  // solid_box's density
constexpr double kPlateThickness = 0.01, kPlateDensity = 7850.0;

/// A jelly cube of side kColumn (ν = 0, Neo-Hookean) on 4 × 5 × 4 cells, its base at y = 0.
Body jelly_column() {
  Body b = test_support::solid_box(Vec3::Constant(kColumn), 4, 5, 4, Vec3(0.0, 0.5 * kColumn, 0.0),
                                   kJellyModulus, 0.0, SolidModel::neo_hookean);
  b.name = "jelly";
  return b;
}

/// A 1 cm steel plate covering the column's top face, its lower side (the mid-surface less the
/// contact offset t/2) `gap` above it, on the top's 4 × 4 cells.
Body steel_plate(double gap) {
  TriangleMesh grid = make_grid(kColumn, kColumn, 4, 4);
  Positions v(grid.num_vertices(), 3);
  v.col(0) = grid.vertices.col(0).array() - 0.5 * kColumn;
  v.col(1).setConstant(kColumn + 0.5 * kPlateThickness + gap);
  v.col(2) = grid.vertices.col(1).array() - 0.5 * kColumn;
  Body b;
  b.name = "plate";
  b.mesh.vertices = v;
  b.mesh.faces = grid.faces;
  b.material.youngs_modulus = 2e11;
  b.material.poisson_ratio = 0.3;
  b.material.thickness = kPlateThickness;
  b.material.density = kPlateDensity;
  return b;
}

/// The vertices of `body` with the given y (its rest height), as a handle of `axes`.
Handle handle_at_height(const Scene& scene, int body, double y, unsigned axes) {
  Handle h;
  h.body = body;
  h.axes = axes;
  const Positions& v = scene.bodies[body].mesh.vertices;
  for (int i = 0; i < v.rows(); ++i)
    if (std::abs(v(i, 1) - y) < 1e-9) h.vertices.push_back(i);
  return h;
}

/// Shortening (m) of a Neo-Hookean column (ν = 0, so λ = 0, μ = E/2, no lateral strain) of
/// height H under its weight and a top pressure p: the nominal stress at reference height Z is
/// −(p + ρ g (H − Z)) and uniaxial ψ = μ/2 (s² − 1) − μ ln s gives P = μ (s − 1/s) (Bonet and
/// Wood 2008, eq. 6.27 with λ = 0), so s = (−q + √(q² + 4))/2 with q = (p + ρ g (H − Z))/μ, and
/// the shortening is ∫₀ᴴ (1 − s) dZ (Simpson's rule, 2000 intervals).
double neo_hookean_column_shortening(double pressure) {
  const double mu = 0.5 * kJellyModulus;
  const auto one_minus_stretch = [&](double z) {
    const double q = (pressure + kJellyDensity * kG * (kColumn - z)) / mu;
    return 1.0 - 0.5 * (-q + std::sqrt(q * q + 4.0));
  };
  const int n = 2000;
  const double h = kColumn / n;
  double sum = one_minus_stretch(0.0) + one_minus_stretch(kColumn);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * one_minus_stretch(i * h);
  return sum * h / 3.0;
}

TEST(MixedBodies, SteelPlateOnAJellyColumnCompressesItAsNeoHookeanTheorySays) {
  // A plate of areal weight p = ρ_s t g = 770 Pa rests on the column's top through the contact
  // barrier. With ν = 0 the column's exact deformation is uniaxial, so clamping its base
  // changes nothing; the plate is held only sideways (x, z), free to sink.
  Scene s;
  s.name = "plate_on_jelly";
  s.mode = StepMode::quasistatic;
  s.time_step = 0.25;
  s.duration = 1.0;
  s.gravity = Vec3(0.0, -kG, 0.0);
  for (Effect e :
       {Effect::elasticity, Effect::membrane, Effect::bending, Effect::gravity, Effect::contact})
    s.effects.enable(e);
  s.contact.dhat = 1e-4;
  s.solver.tolerance = 1e-8;
  s.bodies = {jelly_column(), steel_plate(5e-5)};
  s.handles.push_back(handle_at_height(s, 0, 0.0, handle_axes_all));
  s.handles.push_back(
      handle_at_height(s, 1, s.bodies[1].mesh.vertices(0, 1), handle_axis_x | handle_axis_z));
  LevelSimulation sim(s);
  std::vector<StepRecord> records = run_checked(sim);
  ASSERT_FALSE(::testing::Test::HasFailure());
  EXPECT_EQ(records.back().newton.stop, NewtonStop::converged);
  double top = 0.0, plate = 0.0;
  int count = 0;
  const Positions& rest = s.bodies[0].mesh.vertices;
  for (int v = 0; v < rest.rows(); ++v)
    if (std::abs(rest(v, 1) - kColumn) < 1e-9) {
      top += sim.positions()(v, 1);
      ++count;
    }
  top /= count;
  const int first_plate_vertex = static_cast<int>(rest.rows());
  plate = sim.positions().bottomRows(sim.positions().rows() - first_plate_vertex).col(1).mean() -
          0.5 * kPlateThickness;  // its lower side
  const double pressure = kPlateDensity * kPlateThickness * kG;
  const double expected = neo_hookean_column_shortening(pressure);
  const double unloaded = neo_hookean_column_shortening(0.0);  // printed: the plate's share
  std::cout << "[ mixed    ] column shortening " << kColumn - top << " m, Neo-Hookean closed form "
            << expected << " m (without the plate " << unloaded << " m); the plate's lower side "
            << plate - top << " m above the top\n";
  EXPECT_NEAR(kColumn - top, expected, 0.005 * expected);  // measured: 0.004 % apart
  EXPECT_GT(plate - top, 0.0);
  EXPECT_LT(plate - top, s.contact.dhat);
}

TEST(MixedBodies, ClothDroppedOnAJellyCubeStaysIntersectionFree) {
  Scene s = load_scene_file(std::string(PROGSIM_SOURCE_DIR) + "/scenes/cloth_on_jelly.json");
  s.duration = 0.3;  // long enough to land and fold over the edges
  LevelSimulation sim(s);
  const int jelly_vertices = s.bodies[0].mesh.num_vertices();
  run_checked(sim);
  ASSERT_FALSE(::testing::Test::HasFailure());
  const auto jelly = sim.positions().topRows(jelly_vertices);
  const auto cloth = sim.positions().bottomRows(sim.positions().rows() - jelly_vertices);
  EXPECT_GT(jelly.col(1).minCoeff(), 0.0);
  EXPECT_LT(cloth.col(1).minCoeff(), jelly.col(1).maxCoeff() - 0.03)
      << "the cloth did not drape over the cube's edges";
  EXPECT_GT(test_support::min_tet_determinant(s.bodies[0].tets, jelly), 0.0)
      << "a tet inverted or went flat";
}

TEST(MixedBodies, ProgressiveRunsOfMixedScenesAreRefusedByName) {
  Scene s = load_scene_file(std::string(PROGSIM_SOURCE_DIR) + "/scenes/cloth_on_jelly.json");
  s.progressive.level_vertices = {200};
  try {
    make_progressive_animation(s);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::unsupported);
    EXPECT_NE(std::string(e.what()).find("mixes shells and volumetric"), std::string::npos)
        << e.what();
  }
  s.mode = StepMode::quasistatic;  // PSQ refuses it the same way
  try {
    ProgressiveSimulation psq(s);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::unsupported);
    EXPECT_NE(std::string(e.what()).find("mixes shells and volumetric"), std::string::npos)
        << e.what();
  }
  // Each kind's effects still need a body of that kind.
  Scene solids_only = s;
  solids_only.bodies.pop_back();
  try {
    validate_scene(solids_only);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'membrane' effect acts on shells"), std::string::npos)
        << e.what();
  }
  Scene shells_only = s;
  shells_only.bodies.erase(shells_only.bodies.begin());
  try {
    validate_scene(shells_only);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'elasticity' effect acts on volumetric"),
              std::string::npos)
        << e.what();
  }
  // One material value for every body would cross kinds.
  try {
    set_scene_parameter(s, "material.youngs_modulus", 1e6);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::unsupported);
  }
}

TEST(MixedBodies, ShellTermsCoverTheShellsAlone) {
  // The membrane and bending terms of the mixed scene are those of its cloth alone: the jelly's
  // boundary faces are no shell. A solid's bending model is not looked at.
  Scene mixed = load_scene_file(std::string(PROGSIM_SOURCE_DIR) + "/scenes/cloth_on_jelly.json");
  mixed.bodies[1].material.bending_model = BendingModel::midedge;
  Scene cloth = mixed;
  cloth.bodies.erase(cloth.bodies.begin());
  cloth.effects.disable(Effect::elasticity);
  const ShellElastics with_jelly = make_shell_elastics(mixed, build_shell_model(mixed), true);
  const ShellElastics alone = make_shell_elastics(cloth, build_shell_model(cloth), true);
  const auto term = [](const ShellElastics& e, const std::string& name) -> const EnergyTerm* {
    for (const auto& t : e.terms)
      if (t->name() == name) return t.get();
    return nullptr;
  };
  for (const char* name : {"membrane", "bending"}) {
    ASSERT_NE(term(with_jelly, name), nullptr) << name;
    EXPECT_EQ(term(with_jelly, name)->hessian_entry_count(),
              term(alone, name)->hessian_entry_count())
        << name;
  }
  EXPECT_NE(dynamic_cast<const MidedgeBending*>(term(with_jelly, "bending")), nullptr);
}

}  // namespace mixed_bodies
