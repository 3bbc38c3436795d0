// A run must not depend on the threads it was given: the automatic thread budget
// (common/thread_budget.hpp) follows the machine's load, so the same simulation may get one
// thread on a busy machine and two on a quiet one, even between two steps of one run.
#include <gtest/gtest.h>

#include "common/thread_budget.hpp"
#include "contact_scene_support.hpp"

using namespace progsim;
using namespace progsim::contact_scenes;

namespace {

/// The cloth's positions after `steps` steps on `threads` threads: 3721 vertices lying 1 mm
/// above a sphere's top (inside d̂: contact and friction from the first step), large enough
/// for every loop to be parallel and for the energy sums to be cut into blocks.
Positions cloth_on_sphere_after(int threads, int steps) {
  Scene scene = cloth_scene(horizontal_cloth(0.6, 60, 0.251), 0.3, 0.01, steps);
  scene.obstacles.push_back(static_obstacle("sphere", make_sphere(0.25, 3), 0.3));
  set_thread_budget(threads);
  LevelSimulation sim(scene);
  for (int s = 0; s < steps; ++s) {
    const StepRecord r = sim.step();
    EXPECT_EQ(r.newton.stop, NewtonStop::converged) << threads << " thread(s), step " << s;
    EXPECT_GT(r.contact->active_pairs, 0) << "step " << s;
  }
  set_thread_budget(0);
  return sim.positions();
}

}  // namespace

TEST(ThreadIndependence, ContactStepsAreTheSameToTheBitOnOneAndTwoThreads) {
  const Positions one = cloth_on_sphere_after(1, 2);
  const Positions two = cloth_on_sphere_after(2, 2);
  ASSERT_TRUE(one.allFinite());
  EXPECT_GT((one - horizontal_cloth(0.6, 60, 0.251).vertices).norm(), 0.0);  // it moved
  EXPECT_TRUE((one.array() == two.array()).all())
      << "max difference " << (one - two).cwiseAbs().maxCoeff();
}
