// Every bundled scene (scenes/*.json) loads, passes its start checks (for contact scenes: no
// intersection by CGAL's exact predicates) and takes a finite first step.
#include <gtest/gtest.h>

#include <filesystem>

#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;

TEST(BundledScenes, EveryOneLoadsAndTakesAFiniteStep) {
  int scenes = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(PROGSIM_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    ++scenes;
    LevelSimulation sim(load_scene_file(entry.path().string()));
    const StepRecord r = sim.step();
    EXPECT_TRUE(sim.dofs().allFinite());
    EXPECT_NE(r.newton.stop, NewtonStop::non_finite);
    EXPECT_EQ(r.contact.has_value(), sim.scene().effects.has(Effect::contact));
  }
  EXPECT_GE(scenes, 5);
}
