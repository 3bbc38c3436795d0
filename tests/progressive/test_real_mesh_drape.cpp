// A real mesh draped progressively (issue 28 point 2): CGAL's mushroom cap (mushroom.off, 2337
// vertices, open), hung from its top over a progressive sphere inside it, its rim 3 mm above
// the ground, under gravity, previewed on 150 vertices and refined through 600 to the finest
// level, which must reach equilibrium. Asserted: every level's state crossing-free by CGAL's
// exact predicates (core/mesh/intersection_check.hpp, shell and sphere as the level met it),
// every vertex above the ground, and the finest level converged. Refinement time is measured by
// bench_real_mesh_drape, not asserted. Needs the CGAL meshes (scripts/fetch_test_meshes.sh).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "mesh/intersection_check.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "support/real_meshes.hpp"

using namespace progsim;
using namespace progsim::test_support;
namespace fs = std::filesystem;

namespace {

/// The cap (0.3 m across, its open rim down) held by the 7 vertices of its flat top within
/// 3 cm of the axis; the sphere 1 cm under the top's inside; the ground 3 mm under the rim.
const char* const kMushroomDrape = R"({
  "name": "mushroom_drape",
  "simulation": {"mode": "quasistatic", "time_step": 1.0, "duration": 4.0},
  "effects": ["membrane", "bending", "gravity", "contact", "friction"],
  "bodies": [{
    "name": "cap",
    "mesh": {"file": "mushroom.off"},
    "transform": {"scale": 0.3, "rotate": {"axis": [1, 0, 0], "degrees": -90},
                  "translate": [0, 0.0726, 0]},
    "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "thickness": 2e-4,
                 "density": 300, "friction": 0.1}}],
  "obstacles": [{"name": "sphere",
                 "mesh": {"generator": "sphere", "radius": 0.06, "subdivisions": 3},
                 "transform": {"translate": [0, 0.0722, 0]}, "friction": 0.1,
                 "progressive": true}],
  "handles": [{"body": "cap", "vertices": [16, 718, 833, 839, 841, 1594, 1731]}],
  "ground": {"normal": [0, 1, 0], "height": 0, "friction": 0.1},
  "contact": {"dhat": 1e-3},
  "progressive": {"levels": [150, 600], "proximal": true}
})";

}  // namespace

TEST(RealMeshDrape, MushroomCapOverASphereRunsToTheConvergedFinestLevel) {
  const fs::path folder = real_mesh_folder();
  ASSERT_TRUE(fs::is_regular_file(folder / "mushroom.off"))
      << folder << " has no mushroom.off: run scripts/fetch_test_meshes.sh (set "
      << "PROGSIM_MESH_CACHE to use another cache folder)";
  const Scene scene = parse_scene(kMushroomDrape, folder.string());
  ProgressiveSimulation psq(scene);
  ASSERT_EQ(psq.finest(), 2);
  for (int k = 0; k < scene.num_steps(); ++k) psq.step();
  for (int level = 0;; ++level) {
    SCOPED_TRACE("level " + std::to_string(level));
    const bool equilibrium = psq.settle_to_equilibrium(level == psq.finest() ? 200 : 20);
    const Positions x = psq.positions(level);
    EXPECT_EQ(psq.current().intersecting_face_pairs(), 0u);  // shell and sphere, CGAL
    EXPECT_TRUE(intersecting_faces(x, psq.hierarchy().levels[level].rest.faces, 1).empty());
    EXPECT_GT(x.col(1).minCoeff(), scene.ground.height);  // above the ground
    EXPECT_TRUE(x.allFinite());
    if (level == psq.finest()) {
      EXPECT_TRUE(equilibrium) << "the finest level did not converge";
      break;
    }
    psq.refine();
    EXPECT_EQ(psq.level(), level + 1);
  }
  // The drape touched what it was meant to: its rim reached the ground's barrier.
  EXPECT_LT(psq.positions(psq.finest()).col(1).minCoeff(), scene.contact.dhat);
}
