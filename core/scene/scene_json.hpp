#pragma once
/// @file The JSON scene format (documented in scenes/README.md, example scenes/*.json).
#include <string>

#include "scene/scene.hpp"

namespace progsim {

/// Parses a scene from JSON text (comments allowed). Relative mesh paths are resolved
/// against base_dir. Unknown keys, missing required fields, wrong types and out-of-range
/// values throw Error(invalid_scene) with the JSON path of the problem
/// ("bodies[0].material.thickness = -1 is invalid: ..."). Meshes are loaded and validated.
Scene parse_scene(const std::string& json_text, const std::string& base_dir);

/// Reads and parses a scene file. Throws Error(io_error) if it cannot be read.
Scene load_scene_file(const std::string& path);

}  // namespace progsim
