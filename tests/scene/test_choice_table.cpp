// The choice table: every named option is reachable by name on a scene, a scene file says the
// same as code, the defaults are the scene's own, and the documentation is generated from it.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "scene/choice_table.hpp"
#include "scene/scene_choices.hpp"
#include "scene/scene_json.hpp"

using namespace progsim;

namespace {

/// A one-body scene whose `section` ("progressive", "simulation" or a body's "material")
/// sets key to value.
std::string scene_with(const std::string& group, const std::string& name,
                       const std::string& value) {
  const std::string entry = "{\"" + name + "\": \"" + value + "\"}";
  const std::string material = group == "material" ? ", \"material\": " + entry : "";
  const std::string section = group == "material" ? "" : ", \"" + group + "\": " + entry;
  return R"({"effects": ["membrane", "bending"], "bodies": [{"mesh": {"generator": "grid",
      "width": 1, "height": 1, "nx": 3, "ny": 3})" +
         material + "}], \"handles\": [{\"body\": 0, \"vertices\": [0]}]" + section + "}";
}

}  // namespace

TEST(ChoiceTable, EveryOptionReadFromAFileEqualsTheSameSetInCode) {
  const Scene defaults = parse_scene(scene_with("progressive", "prolongation", "composed"), ".");
  for (const ChoiceSpec& spec : choice_table()) {
    const std::string name = std::string(spec.group) + "." + spec.name;
    EXPECT_EQ(scene_choice(defaults, name), spec.options[spec.default_index])
        << name << ": the default";
    for (const std::string& option : spec.options) {
      const Scene read = parse_scene(scene_with(spec.group, spec.name, option), ".");
      Scene set = defaults;
      set_scene_choice(set, name, option);
      EXPECT_EQ(scene_choice(read, name), option) << name;
      EXPECT_EQ(scene_choice(set, name), option) << name;
    }
  }
}

TEST(ChoiceTable, TheOptionsLandInTheScenesFields) {
  Scene scene = parse_scene(scene_with("progressive", "proxy_hessian", "galerkin"), ".");
  EXPECT_EQ(scene.progressive.hessian, ProxyHessian::galerkin);
  set_scene_choice(scene, "progressive.prolongation", "direct");
  EXPECT_EQ(scene.progressive.prolongation, ProxyProlongation::direct);
  set_scene_choice(scene, "progressive.preview_membrane", "tension_field");
  EXPECT_EQ(scene.progressive.preview_membrane, MembraneModel::tension_field);
  set_scene_choice(scene, "progressive.prediction", "per_frame");
  EXPECT_EQ(scene.progressive.prediction, DynamicsPrediction::per_frame);
  set_scene_choice(scene, "material.bending_model", "midedge");
  EXPECT_EQ(scene.bodies.front().material.bending_model, BendingModel::midedge);
  set_scene_choice(scene, "simulation.mode", "quasistatic");
  EXPECT_EQ(scene.mode, StepMode::quasistatic);
}

TEST(ChoiceTable, UnknownNamesAndValuesAreRefusedListingTheKnownOnes) {
  Scene scene = parse_scene(scene_with("progressive", "prolongation", "composed"), ".");
  const Scene before = scene;
  try {
    set_scene_choice(scene, "progressive.proxy_hessian", "exact");
    FAIL() << "an unknown value was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::invalid_argument);
    EXPECT_NE(std::string(e.what()).find(
                  "progressive.proxy_hessian: unknown 'exact' (known: auto, level, galerkin)"),
              std::string::npos)
        << e.what();
  }
  try {
    set_scene_choice(scene, "progressive.smoothing", "on");
    FAIL() << "an unknown name was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("known: simulation.mode"), std::string::npos) << e.what();
  }
  EXPECT_EQ(scene.progressive.hessian, before.progressive.hessian);
  EXPECT_THROW(scene_choice(scene, "prolongation"), Error);
}

TEST(ChoiceTable, SceneDocumentationShowsTheGeneratedTable) {
  std::ifstream in(std::string(PROGSIM_SOURCE_DIR) + "/scenes/README.md");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(choice_table_markdown()), std::string::npos)
      << "scenes/README.md is out of date; paste the output of `progsim params`";
}

TEST(ChoiceTable, ASceneBuiltInCodeStartsAtTheTablesDefaults) {
  // Scene{} and ShellMaterial{} are what ps_sim_create and C++ users start from: they must say
  // what a scene file that names no option says.
  Scene code;  // without bodies first: material options read ShellMaterial{}
  for (int bodies : {0, 1}) {
    if (bodies) code.bodies.push_back(Body{});
    for (const ChoiceSpec& spec : choice_table()) {
      const std::string name = std::string(spec.group) + "." + spec.name;
      EXPECT_EQ(scene_choice(code, name), spec.options[spec.default_index]) << name;
    }
  }
}
