// ps_param_*: the parameters ps_sim_set_param() accepts, from the one parameter table plus
// gravity and pressure.
#include <limits>
#include <string>
#include <vector>

#include "api_guard.hpp"
#include "scene/parameter_table.hpp"

namespace progsim::capi {
namespace {

/// Every settable parameter, built once: the table's entries, then the scene vectors.
const std::vector<ps_param_info>& parameter_infos() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const ParameterSpec& spec : parameter_table())
      n.push_back(std::string(spec.group) + "." + spec.name);
    return n;
  }();
  static const std::vector<ps_param_info> infos = [] {
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::vector<ps_param_info> all;
    const std::vector<ParameterSpec>& table = parameter_table();
    for (std::size_t i = 0; i < table.size(); ++i) {
      const ParameterSpec& s = table[i];
      all.push_back({names[i].c_str(), s.unit, s.doc, s.default_value, s.min, s.max,
                     s.min_inclusive, s.max_inclusive, s.integer});
    }
    const char* axis_doc = "Component of the gravitational acceleration.";
    all.push_back({"gravity.x", "m/s^2", axis_doc, 0.0, -inf, inf, 0, 0, 0});
    all.push_back({"gravity.y", "m/s^2", axis_doc, -9.81, -inf, inf, 0, 0, 0});
    all.push_back({"gravity.z", "m/s^2", axis_doc, 0.0, -inf, inf, 0, 0, 0});
    all.push_back({"pressure", "Pa", "Inner pressure of every body (needs the pressure effect).",
                   0.0, -inf, inf, 0, 0, 0});
    return all;
  }();
  return infos;
}

}  // namespace
}  // namespace progsim::capi

using namespace progsim::capi;

extern "C" {

PS_API int32_t ps_param_count(void) {
  return static_cast<int32_t>(parameter_infos().size());
}

PS_API int32_t ps_param_info_get(int32_t index, ps_param_info* out) {
  return guarded(nullptr, "ps_param_info_get", [&] {
    require(out, "out");
    const auto n = static_cast<int32_t>(parameter_infos().size());
    if (index < 0 || index >= n)
      api_fail(PS_ERROR_OUT_OF_RANGE, "parameter " + std::to_string(index) +
                                          " does not exist (0 to " + std::to_string(n - 1) + ")");
    *out = parameter_infos()[index];
  });
}

}  // extern "C"
