// Issue 28's one rule for a crossing input: with contact on, a finest mesh that crosses itself
// is refused before any work on every path, naming a crossing pair of the input, unless the
// scene sets contact.crossing_start, which only a progressive run honours; then every level's
// state is crossing-free (CGAL's exact check, independent of the contact code that keeps it).
#include <gtest/gtest.h>

#include "mesh/intersection_check.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "sim/shell_model.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using namespace progsim::test_support;

namespace {

Scene crossing_flap() {
  return load_scene_file(PROGSIM_TEST_DATA_DIR "/crossing_flap.json");
}

bool count_calls(void* user, double, const char*) {
  ++*static_cast<int*>(user);
  return true;
}

/// The flap's centre vertex, the one dipping through the sheet (13 × 13 sheet vertices first).
constexpr int kDip = 169 + 2 * 5 + 2;

TEST(CrossingStart, TheInputCrossesOnlyAroundTheDip) {
  const ShellModel model = build_shell_model(crossing_flap());
  const auto pairs = intersecting_faces(model.rest.vertices, model.rest.faces);
  ASSERT_FALSE(pairs.empty());
  const auto has_dip = [&](int f) { return (model.rest.faces.row(f).array() == kDip).any(); };
  for (const FacePair& p : pairs) EXPECT_TRUE(has_dip(p.a) != has_dip(p.b)) << p.a << ", " << p.b;
}

TEST(CrossingStart, AProgressiveRunIsRefusedBeforeBuildingAnything) {
  int progress_calls = 0;
  expect_error(
      [&] { ProgressiveSimulation psq(crossing_flap(), nullptr, count_calls, &progress_calls); },
      Status::intersecting, {"crossing_flap: the input mesh: shell face ", " cross"});
  EXPECT_EQ(progress_calls, 0) << "the hierarchy was being built";
}

TEST(CrossingStart, ADirectRunIsRefusedEvenWithTheOptIn) {
  Scene scene = crossing_flap();
  scene.contact.crossing_start = true;
  expect_error([&] { LevelSimulation sim(scene); }, Status::intersecting,
               {"crossing_flap: the start intersects: shell face "});
}

TEST(CrossingStart, WithTheOptInEveryLevelIsCrossingFree) {
  Scene scene = crossing_flap();
  scene.contact.crossing_start = true;
  ProgressiveSimulation psq(scene);
  const ShellModel model = build_shell_model(scene);
  EXPECT_EQ(psq.input_crossing_pairs(),
            static_cast<int>(intersecting_faces(model.rest.vertices, model.rest.faces).size()));
  for (int level = 0;; ++level) {
    EXPECT_EQ(psq.current().intersecting_face_pairs(), 0u) << "start of level " << level;
    if (level == 0) psq.step();
    psq.settle_to_equilibrium(30);
    EXPECT_EQ(psq.current().intersecting_face_pairs(), 0u) << "level " << level;
    if (level == psq.finest()) break;
    psq.refine();
  }
  const TriangleMesh& fine = psq.hierarchy().levels.back().rest;
  EXPECT_TRUE(intersecting_faces(psq.positions(psq.finest()), fine.faces).empty());
}

}  // namespace
