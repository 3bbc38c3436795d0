// The JSON scene format: bundled scenes parse; every malformed scene names its problem.
#include <gtest/gtest.h>

#include <string>

#include "common/error.hpp"
#include "energy/shell_material.hpp"
#include "scene/parameter_table.hpp"
#include "scene/scene_json.hpp"

using namespace progsim;

namespace {

/// A small valid scene; `body_extra` is spliced into the body object, `top_extra` into the root.
const char* const kGrid = R"({ "generator": "grid", "width": 1, "height": 1, "nx": 3, "ny": 3 })";

std::string scene_text(const std::string& body_extra = "", const std::string& top_extra = "",
                       const std::string& effects = R"(["membrane", "gravity"])",
                       const std::string& mesh = kGrid) {
  return R"({ "name": "t", "effects": )" + effects + top_extra + R"(,
    "bodies": [ { "name": "sheet", "mesh": )" +
         mesh + body_extra + R"( } ] })";
}

/// Parses and returns the error (status and message) it must raise.
Error parse_error(const std::string& text) {
  try {
    parse_scene(text, ".");
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "scene parsed but should have failed:\n" << text;
  return Error(Status::ok, "");
}

void expect_scene_error(const std::string& text, const std::string& needle) {
  const Error e = parse_error(text);
  EXPECT_EQ(e.status(), Status::invalid_scene) << e.what();
  EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
      << "message '" << e.what() << "' lacks '" << needle << "'";
}

}  // namespace

TEST(SceneJson, BundledScenesParse) {
  // Parsing validates: none is refused, e.g. as a free quasistatic body (the balloon is held
  // by its closed surface's balanced pressure, the drape by its centre handle and contact).
  for (const char* name :
       {"hanging_cloth", "curved_shell", "balloon", "cloth_on_sphere", "twisted_cloth",
        "vpd_twisted_bar", "vpd_jelly_drop", "psq_balloon", "psq_can_crush", "psq_cloth_on_sphere",
        "psq_plate_buckling", "psq_twist", "pd_drape", "pd_cube_on_sheet", "pd_spin_cycle"}) {
    const Scene scene =
        load_scene_file(std::string(PROGSIM_SOURCE_DIR) + "/scenes/" + name + ".json");
    EXPECT_EQ(scene.name, name);
    EXPECT_FALSE(scene.bodies.empty());
  }
}

TEST(SceneJson, RefusesAFreeQuasistaticBodyNamingIt) {
  const std::string quasistatic = R"(, "simulation": {"mode": "quasistatic"})";
  // Gravity pulls the sheet and nothing holds it: no load step has an equilibrium.
  expect_scene_error(scene_text("", quasistatic), "body 'sheet' (bodies[0]) is free");
  expect_scene_error(scene_text("", quasistatic), "proximal");  // says how to hold it
  // Pressure on an open sheet pulls it too; on a closed sphere it balances.
  const std::string pressure = R"(["membrane", "pressure"])";
  expect_scene_error(scene_text(R"(, "pressure": 100)", quasistatic, pressure),
                     "pressure on its open surface");
  EXPECT_NO_THROW(
      parse_scene(scene_text(R"(, "pressure": 100)", quasistatic, pressure,
                             R"({"generator": "sphere", "radius": 0.1, "subdivisions": 1})"),
                  "."));
  // Held: a handle, a ground to rest on with contact, the proximal term, no load, dynamics.
  EXPECT_NO_THROW(parse_scene(
      scene_text("", quasistatic + R"(, "handles": [{"body": "sheet", "vertices": [0]}])"), "."));
  EXPECT_NO_THROW(parse_scene(scene_text("", quasistatic + R"(, "ground": {"height": -1})",
                                         R"(["membrane", "gravity", "contact"])"),
                              "."));
  EXPECT_NO_THROW(
      parse_scene(scene_text("", quasistatic + R"(, "progressive": {"proximal": true})"), "."));
  EXPECT_NO_THROW(parse_scene(scene_text("", quasistatic, R"(["membrane"])"), "."));
  EXPECT_NO_THROW(parse_scene(scene_text(), "."));
  // A ground without the contact effect holds nothing (and is refused for that already).
  expect_scene_error(scene_text("", quasistatic + R"(, "ground": {"height": -1})"), "contact");
}

TEST(SceneJson, ReadsMaterialsHandlesAndDefaults) {
  const Scene s =
      parse_scene(scene_text(R"(, "material": {"thickness": 0.002, "youngs_modulus": 3e6,
                                                "bending_youngs_modulus": 4e7})",
                             R"(, "handles": [{"body": "sheet", "vertices": [0, 3],
                                              "motion": {"velocity": [0, 1, 0]}}])"),
                  ".");
  EXPECT_EQ(s.bodies[0].material.thickness, 0.002);
  EXPECT_EQ(s.bodies[0].material.youngs_modulus, 3e6);
  EXPECT_EQ(s.bodies[0].material.bending_youngs_modulus, 4e7);
  EXPECT_EQ(s.bodies[0].material.poisson_ratio,
            find_parameter("material", "poisson_ratio").default_value);
  ASSERT_EQ(s.handles.size(), 1u);
  EXPECT_EQ(s.handles[0].vertices, (std::vector<int>{0, 3}));
  EXPECT_EQ(s.handles[0].motion.velocity, Vec3(0, 1, 0));
  EXPECT_TRUE(s.effects.has(Effect::membrane));
  EXPECT_FALSE(s.effects.has(Effect::bending));
  EXPECT_EQ(s.time_step, find_parameter("simulation", "time_step").default_value);
}

TEST(SceneJson, ReadsTheSolverSection) {
  const Scene defaults = parse_scene(scene_text(), ".");
  EXPECT_EQ(defaults.solver.max_cg_iterations, 0);  // CG refinement is opt-in
  const Scene s = parse_scene(
      scene_text("", R"(, "solver": {"max_newton_iterations": 40, "max_cg_iterations": 25})"), ".");
  EXPECT_EQ(s.solver.max_iterations, 40);
  EXPECT_EQ(s.solver.max_cg_iterations, 25);
  expect_scene_error(scene_text("", R"(, "solver": {"max_cg_iterations": -1})"),
                     "solver.max_cg_iterations");
  expect_scene_error(scene_text("", R"(, "solver": {"max_cg_iterations": 1.5})"), "whole number");
  EXPECT_TRUE(defaults.solver.extrapolate);  // line-search extrapolation is on by default
  EXPECT_FALSE(parse_scene(scene_text("", R"(, "solver": {"line_search_extrapolation": 0})"), ".")
                   .solver.extrapolate);
  expect_scene_error(scene_text("", R"(, "solver": {"line_search_extrapolation": 2})"),
                     "solver.line_search_extrapolation");
}

TEST(SceneJson, ShellMaterialDefaultsAgreeWithTheParameterTable) {
  const ShellMaterial m;
  EXPECT_EQ(m.youngs_modulus, find_parameter("material", "youngs_modulus").default_value);
  EXPECT_EQ(m.bending_youngs_modulus,
            find_parameter("material", "bending_youngs_modulus").default_value);
  EXPECT_EQ(m.poisson_ratio, find_parameter("material", "poisson_ratio").default_value);
  EXPECT_EQ(m.thickness, find_parameter("material", "thickness").default_value);
  EXPECT_EQ(m.density, find_parameter("material", "density").default_value);
}

TEST(SceneJson, RejectsMissingFields) {
  expect_scene_error(R"({ "effects": ["membrane"] })", "missing required field 'bodies'");
  expect_scene_error(R"({ "bodies": [] })", "missing required field 'effects'");
  expect_scene_error(R"({ "effects": [], "bodies": [ {"name": "a"} ] })",
                     "missing required field 'mesh'");
  expect_scene_error(scene_text("", "", R"(["membrane"])",
                                R"({"generator": "grid", "width": 1, "height": 1, "ny": 3})"),
                     "missing required field 'nx'");
}

TEST(SceneJson, RejectsGeneratedMeshesTooLargeToBuild) {
  const std::string grid =
      R"({"generator": "grid", "width": 1, "height": 1, "nx": 8000, "ny": 8000})";
  expect_scene_error(scene_text("", "", R"(["membrane"])", grid), "nx·ny at most 5e7");
  const std::string cylinder = R"({"generator": "cylinder", "radius": 1, "length": 1,
                                   "n_around": 100000, "n_along": 100000})";
  expect_scene_error(scene_text("", "", R"(["membrane"])", cylinder),
                     "n_around·n_along at most 5e7");
}

TEST(SceneJson, RejectsOutOfRangeMaterials) {
  expect_scene_error(scene_text(R"(, "material": {"thickness": -0.001})"),
                     "bodies[0].material.thickness");
  expect_scene_error(scene_text(R"(, "material": {"poisson_ratio": 0.5})"),
                     "poisson_ratio = 0.5 is invalid");
  expect_scene_error(scene_text(R"(, "material": {"poisson_ratio": 0.7})"), "(-1, 0.5)");
  expect_scene_error(scene_text(R"(, "material": {"youngs_modulus": 0})"), "youngs_modulus");
  expect_scene_error(scene_text(R"(, "material": {"bending_youngs_modulus": -1})"),
                     "bodies[0].material.bending_youngs_modulus");
  expect_scene_error(scene_text(R"(, "material": {"density": "heavy"})"), "must be a number");
}

TEST(SceneJson, RejectsUnknownEffectsKeysAndModes) {
  expect_scene_error(scene_text("", "", R"(["membrane", "magnetism"])"),
                     "unknown effect 'magnetism'");
  expect_scene_error(scene_text(R"(, "material": {"thicknes": 0.001})"), "unknown key 'thicknes'");
  expect_scene_error(scene_text("", R"(, "simulation": {"mode": "fast"})"),
                     "simulation.mode: unknown 'fast' (known: dynamic, quasistatic)");
  expect_scene_error(scene_text("", R"(, "simulation": {"time_step": 0})"), "simulation.time_step");
  expect_scene_error(scene_text("", R"(, "solver": {"max_newton_iterations": 2.5})"),
                     "whole number");
}

TEST(SceneJson, RejectsBadHandles) {
  expect_scene_error(scene_text("", R"(, "handles": [{"body": "nobody", "vertices": [0]}])"),
                     "names no body");
  expect_scene_error(scene_text("", R"(, "handles": [{"body": 0, "vertices": [99]}])"),
                     "vertex 99 is out of range");
  expect_scene_error(
      scene_text("", R"(, "handles": [{"body": 0, "box": {"min": [5,5,5], "max": [6,6,6]}}])"),
      "selects no vertices");
}

TEST(SceneJson, RejectsInvalidJsonAndMissingFiles) {
  expect_scene_error("{ \"effects\": [", "not valid JSON");
  const Error missing =
      parse_error(scene_text("", "", R"(["membrane"])", R"({ "file": "does/not/exist.obj" })"));
  EXPECT_EQ(missing.status(), Status::io_error) << missing.what();
  EXPECT_NE(std::string(missing.what()).find("does/not/exist.obj"), std::string::npos);
  try {
    load_scene_file("/nonexistent/scene.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::io_error);
  }
}

TEST(SceneJson, ReadsTheProgressiveSection) {
  const Scene scene =
      parse_scene(scene_text("", R"(, "progressive": {"coarse_levels": 2, "coarsening_ratio": 3.5,
                       "preview_iterations": 4, "preview_tolerance": 1e-4,
                       "prolongation": "direct", "proxy_hessian": "galerkin",
                       "proximal": true, "preview_membrane": "tension_field",
                       "galerkin_refresh": 0.5})"),
                  ".");
  EXPECT_EQ(scene.progressive.coarse_levels, 2);
  EXPECT_EQ(scene.progressive.coarsening_ratio, 3.5);
  EXPECT_EQ(scene.progressive.preview_iterations, 4);
  EXPECT_EQ(scene.progressive.preview_tolerance, 1e-4);
  EXPECT_EQ(scene.progressive.prolongation, ProxyProlongation::direct);
  EXPECT_EQ(scene.progressive.hessian, ProxyHessian::galerkin);
  EXPECT_EQ(scene.progressive.galerkin_refresh, 0.5);
  EXPECT_TRUE(scene.progressive.proximal);
  EXPECT_EQ(scene.progressive.preview_membrane, MembraneModel::tension_field);
  EXPECT_TRUE(scene.progressive.enabled());
  const Scene levels = parse_scene(scene_text("", R"(, "progressive": {"levels": [5, 9]})"), ".");
  EXPECT_EQ(levels.progressive.level_vertices, (std::vector<int>{5, 9}));
  EXPECT_EQ(levels.progressive.prolongation, ProxyProlongation::composed);
  EXPECT_FALSE(levels.progressive.proximal);
  EXPECT_EQ(levels.progressive.preview_iterations, 8);  // the table's default
  EXPECT_TRUE(parse_scene(scene_text("", R"(, "progressive": {"levels": [5], "proximal": 1})"), ".")
                  .progressive.proximal);  // 1/0 as a table switch
  EXPECT_EQ(levels.progressive.preview_membrane, MembraneModel::neo_hookean);
  EXPECT_EQ(levels.progressive.hessian, ProxyHessian::automatic);
  EXPECT_EQ(levels.progressive.galerkin_refresh, 0.5);
  const Scene automatic = parse_scene(
      scene_text("", R"(, "progressive": {"levels": [5], "proxy_hessian": "auto"})"), ".");
  EXPECT_EQ(automatic.progressive.hessian, ProxyHessian::automatic);
  EXPECT_FALSE(parse_scene(scene_text(), ".").progressive.enabled());
}

TEST(SceneJson, RejectsBadProgressiveSettings) {
  expect_scene_error(scene_text("", R"(, "progressive": {"levles": [5]})"), "unknown key 'levles'");
  expect_scene_error(scene_text("", R"(, "progressive": {"coarse_levels": -1})"), "coarse_levels");
  expect_scene_error(scene_text("", R"(, "progressive": {"coarsening_ratio": 1})"),
                     "coarsening_ratio");
  expect_scene_error(scene_text("", R"(, "progressive": {"levels": [2]})"), "too small");
  expect_scene_error(scene_text("", R"(, "progressive": {"galerkin_refresh": -0.1})"),
                     "galerkin_refresh");
  expect_scene_error(scene_text("", R"(, "progressive": {"preview_iterations": 0})"),
                     "progressive.preview_iterations");
  expect_scene_error(scene_text("", R"(, "progressive": {"preview_iterations": 2.5})"),
                     "whole number");
  expect_scene_error(scene_text("", R"(, "progressive": {"preview_tolerance": 2})"),
                     "progressive.preview_tolerance");
  expect_scene_error(scene_text("", R"(, "progressive": {"proximal": 2})"), "progressive.proximal");
  expect_scene_error(scene_text("", R"(, "progressive": {"prolongation": "cubic"})"),
                     "unknown 'cubic'");
  expect_scene_error(scene_text("", R"(, "progressive": {"proxy_hessian": "exact"})"),
                     "unknown 'exact'");
  expect_scene_error(scene_text("", R"(, "progressive": {"preview_membrane": "linear"})"),
                     "unknown 'linear' (known: neo_hookean, tension_field)");
  expect_scene_error(scene_text("", R"(, "progressive": {"preview_iterations": 0})"),
                     "preview_iterations");
  expect_scene_error(scene_text("", R"(, "progressive": {"proximal": "yes"})"), "proximal");
}
