// Builds a tiny scene against the installed library and takes one step.
#include <cmath>
#include <cstdio>

#include "common/build_info.hpp"
#include "mesh/mesh_generators.hpp"
#include "sim/level_simulation.hpp"

int main() {
  progsim::Scene scene;
  scene.effects.enable(progsim::Effect::membrane);
  scene.effects.enable(progsim::Effect::gravity);
  scene.bodies.push_back({"sheet", progsim::make_grid(1.0, 1.0, 4, 4), {}, 0.0, 0.0});
  progsim::LevelSimulation sim(scene);
  sim.step();
  const double y = sim.positions()(12, 1);  // the centre vertex (2, 2) of the 5 × 5 grid
  std::printf("progsim %s consumer: centre y after one step = %g\n", progsim::version_string(), y);
  return (std::isfinite(y) && y < 0.5) ? 0 : 1;  // the centre vertex starts at y = 0.5
}
