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

/// `text` with every match of `pattern` replaced by `replace(match)`.
template <class Replace>
std::string replace_matches(const std::string& text, const std::regex& pattern, Replace replace) {
  std::string out;
  std::size_t last = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), pattern), end; it != end; ++it) {
    const std::smatch& m = *it;
    out += text.substr(last, m.position(0) - last) + replace(m);
    last = m.position(0) + m.length(0);
  }
  return out + text.substr(last);
}

/// The scene file with its generated mesh's cell counts ("nx", "ny", "n_around", "n_along", and
/// each of a tet box's "cells") multiplied by `factor`.
inline Scene scaled_scene(const std::string& path, double factor) {
  std::ifstream file(path);
  if (!file) fail(Status::io_error, "cannot read scene file '" + path + "'");
  std::stringstream text;
  text << file.rdbuf();
  const auto scaled = [factor](const std::string& cells) {
    return std::to_string(std::lround(std::stod(cells) * factor));
  };
  const std::regex count("\"(nx|ny|n_around|n_along)\": *([0-9]+)");
  const std::regex box("\"cells\": *\\[ *([0-9]+) *, *([0-9]+) *, *([0-9]+) *\\]");
  std::string json = replace_matches(text.str(), count, [&](const std::smatch& m) {
    return "\"" + m[1].str() + "\": " + scaled(m[2].str());
  });
  json = replace_matches(json, box, [&](const std::smatch& m) {
    return "\"cells\": [" + scaled(m[1].str()) + ", " + scaled(m[2].str()) + ", " +
           scaled(m[3].str()) + "]";
  });
  return parse_scene(json, path.substr(0, path.find_last_of('/') + 1));
}

}  // namespace progsim
