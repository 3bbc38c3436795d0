#pragma once
/// @file Access to the parameter table in parameters.def.
#include <string>
#include <vector>

namespace progsim {

/// One numeric parameter: its default, unit, admissible range and documentation.
struct ParameterSpec {
  const char* group;  ///< "simulation", "material", "solver"
  const char* name;
  double default_value;
  const char* unit;
  double min;
  bool min_inclusive;
  double max;
  bool max_inclusive;
  bool integer;  ///< only whole numbers are admissible
  const char* doc;
};

/// Every parameter, in table order.
const std::vector<ParameterSpec>& parameter_table();

/// The parameter group.name. Throws Error(invalid_argument) if there is none.
const ParameterSpec& find_parameter(const std::string& group, const std::string& name);

/// Throws Error(invalid_scene) naming the parameter (label, or group.name if empty), the
/// value and the admissible range if value is not finite, outside the range, or not whole
/// for an integer parameter.
void check_parameter(const ParameterSpec& spec, double value, const std::string& label = "");

/// The range as text, e.g. "(0, 0.5)" or "[1, 1e+06]".
std::string range_text(const ParameterSpec& spec);

/// The table as Markdown (name, default, unit, range, doc) for docs and `progsim params`.
std::string parameter_table_markdown();

}  // namespace progsim
