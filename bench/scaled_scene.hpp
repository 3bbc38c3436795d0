#pragma once
/// @file Benchmarks' bundled scenes at other sizes: the mesh generator's cell counts scaled.
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "common/error.hpp"
#include "scene/scene_json.hpp"

namespace progsim {

/// The scene file with its generated mesh's cell counts ("nx", "ny", "n_around", "n_along")
/// multiplied by `factor`.
inline Scene scaled_scene(const std::string& path, double factor) {
  std::ifstream file(path);
  if (!file) fail(Status::io_error, "cannot read scene file '" + path + "'");
  std::stringstream text;
  text << file.rdbuf();
  const std::string json = text.str();
  const std::regex count("\"(nx|ny|n_around|n_along)\": *([0-9]+)");
  std::string out;
  std::sregex_iterator it(json.begin(), json.end(), count), end;
  std::size_t last = 0;
  for (; it != end; ++it) {
    const std::smatch& m = *it;
    const long cells = std::lround(std::stod(m[2].str()) * factor);
    out += json.substr(last, m.position(0) - last) + "\"" + m[1].str() +
           "\": " + std::to_string(cells);
    last = m.position(0) + m.length(0);
  }
  out += json.substr(last);
  return parse_scene(out, path.substr(0, path.find_last_of('/') + 1));
}

}  // namespace progsim
