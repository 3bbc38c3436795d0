#pragma once
/// @file Reading and writing a scene's numeric parameters by name, between steps: the
/// parameter table's names ("material.thickness", ...) plus gravity and pressure.
#include <string>

#include "scene/scene.hpp"

namespace progsim {

/// Sets parameter `name` of the scene: a parameter-table name (material.* applies to every
/// body), "gravity.x|y|z" (m/s²) or "pressure" (Pa, every body). Checks the value against
/// the table's range. Throws Error(invalid_argument) for an unknown name (listing the known
/// ones) or an inadmissible value; the scene is unchanged then.
void set_scene_parameter(Scene& scene, const std::string& name, double value);

/// The value of parameter `name` (names as in set_scene_parameter(); material.* and
/// pressure read the first body). Throws Error(invalid_argument) for an unknown name.
double scene_parameter(const Scene& scene, const std::string& name);

}  // namespace progsim
