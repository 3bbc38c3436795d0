#pragma once
/// @file Reading and writing a scene's named options by name (the choice table's
/// "progressive.prolongation", ...), as scene_parameters.hpp does for numbers.
#include <string>

#include "scene/scene.hpp"

namespace progsim {

/// Sets option `name` ("group.name" of choices.def; material.* applies to every body) to
/// `value`, one of its options. Throws Error(invalid_argument) for an unknown name or value,
/// listing the known ones; the scene is unchanged then.
void set_scene_choice(Scene& scene, const std::string& name, const std::string& value);

/// The option `name` of the scene (material.* reads the first body). Throws
/// Error(invalid_argument) for an unknown name.
const std::string& scene_choice(const Scene& scene, const std::string& name);

}  // namespace progsim
