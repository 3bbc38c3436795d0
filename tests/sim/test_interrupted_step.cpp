// A caller's interrupt (a time limit) stops a step inside its Newton solve, at an accepted
// iterate, and the simulation goes on from there once it is lifted.
#include <gtest/gtest.h>

#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"

using namespace progsim;

TEST(InterruptedStep, StopsInsideTheSolveAndGoesOnOnceLifted) {
  // The plate's first load step (its clamped sides close in) takes several Newton iterations.
  const Scene plate = load_scene_file(PROGSIM_SOURCE_DIR "/scenes/psq_plate_buckling.json");
  LevelSimulation whole(plate);
  const StepRecord full = whole.step();
  ASSERT_GT(full.newton.iterations, 2);
  ASSERT_EQ(full.newton.stop, NewtonStop::converged);

  LevelSimulation sim(plate);
  int checks = 0;
  sim.set_interrupt([&] { return ++checks > 2; });
  const StepRecord cut = sim.step();
  EXPECT_EQ(cut.newton.stop, NewtonStop::interrupted);
  EXPECT_EQ(cut.newton.iterations, 2);
  EXPECT_FALSE(cut.equilibrium);
  EXPECT_TRUE(sim.dofs().allFinite());
  EXPECT_GT((sim.dofs() - whole.dofs()).norm(), 0.0);  // stopped short of the solution
  const StepRecord again = sim.settle();               // still interrupted: nothing moves
  EXPECT_EQ(again.newton.iterations, 0);
  EXPECT_EQ(again.change_rms, 0.0);

  sim.set_interrupt({});
  const StepRecord resumed = sim.settle();
  EXPECT_EQ(resumed.newton.stop, NewtonStop::converged);
  EXPECT_LT((sim.dofs() - whole.dofs()).lpNorm<Eigen::Infinity>(),
            10.0 * plate.solver.tolerance * sim.characteristic_length());
}
