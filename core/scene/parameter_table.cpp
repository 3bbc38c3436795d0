#include "scene/parameter_table.hpp"

#include <cmath>
#include <sstream>

#include "common/error.hpp"

namespace progsim {

const std::vector<ParameterSpec>& parameter_table() {
  static const std::vector<ParameterSpec> table = {
#define PROGSIM_PARAMETER(group, name, def, unit, lo, lo_in, hi, hi_in, integer, doc) \
  {#group, #name, def, unit, lo, lo_in, hi, hi_in, integer, doc},
#include "scene/parameters.def"
#undef PROGSIM_PARAMETER
  };
  return table;
}

const ParameterSpec& find_parameter(const std::string& group, const std::string& name) {
  for (const ParameterSpec& spec : parameter_table())
    if (group == spec.group && name == spec.name) return spec;
  fail(Status::invalid_argument, "unknown parameter '" + group + "." + name + "'");
}

std::string range_text(const ParameterSpec& spec) {
  std::ostringstream out;
  out << (spec.min_inclusive ? '[' : '(') << spec.min << ", " << spec.max
      << (spec.max_inclusive ? ']' : ')');
  return out.str();
}

void check_parameter(const ParameterSpec& spec, double value, const std::string& label) {
  const bool above_min = spec.min_inclusive ? value >= spec.min : value > spec.min;
  const bool below_max = spec.max_inclusive ? value <= spec.max : value < spec.max;
  const bool whole = !spec.integer || value == std::floor(value);
  if (std::isfinite(value) && above_min && below_max && whole) return;
  std::ostringstream msg;
  msg << (label.empty() ? std::string(spec.group) + "." + spec.name : label) << " = " << value
      << " is invalid: it must be " << (spec.integer ? "a whole number " : "a finite number ")
      << "in " << range_text(spec) << " " << spec.unit;
  fail(Status::invalid_scene, msg.str());
}

std::string parameter_table_markdown() {
  std::ostringstream out;
  out << "| parameter | default | unit | range | meaning |\n|---|---|---|---|---|\n";
  for (const ParameterSpec& s : parameter_table())
    out << "| `" << s.group << "." << s.name << "` | " << s.default_value << " | " << s.unit
        << " | " << range_text(s) << " | " << s.doc << " |\n";
  return out.str();
}

}  // namespace progsim
