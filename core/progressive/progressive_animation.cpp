#include "progressive/progressive_animation.hpp"

#include "progressive/progressive_dynamics.hpp"
#include "progressive/volumetric_dynamics.hpp"

namespace progsim {

std::unique_ptr<ProgressiveAnimation> make_progressive_animation(Scene scene) {
  if (!all_solid(scene))
    return std::make_unique<ProgressiveDynamics>(std::move(scene));  // refuses mixed scenes
  auto hierarchy = std::make_shared<const TetHierarchy>(build_scene_tet_hierarchy(scene));
  return std::make_unique<VolumetricDynamics>(std::move(scene), std::move(hierarchy));
}

}  // namespace progsim
