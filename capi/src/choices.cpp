// ps_choice_*, ps_sim_set_choice, ps_sim_get_choice: the named options of the choice table
// (core/scene/choices.def), as ps_param_* and ps_sim_set_param are for numbers.
#include <string>
#include <vector>

#include "handles.hpp"
#include "scene/choice_table.hpp"
#include "scene/scene_choices.hpp"

namespace progsim::capi {
namespace {

/// Every named option, built once with static strings.
const std::vector<ps_choice_info>& choice_infos() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const ChoiceSpec& spec : choice_table())
      n.push_back(std::string(spec.group) + "." + spec.name);
    return n;
  }();
  static const std::vector<std::string> options = [] {
    std::vector<std::string> all;
    for (const ChoiceSpec& spec : choice_table()) {
      std::string joined;
      for (const std::string& o : spec.options) joined += (joined.empty() ? "" : "|") + o;
      all.push_back(joined);
    }
    return all;
  }();
  static const std::vector<ps_choice_info> infos = [] {
    std::vector<ps_choice_info> all;
    const std::vector<ChoiceSpec>& table = choice_table();
    for (std::size_t i = 0; i < table.size(); ++i)
      all.push_back({names[i].c_str(), options[i].c_str(),
                     table[i].options[table[i].default_index].c_str(), table[i].doc});
    return all;
  }();
  return infos;
}

}  // namespace
}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API int32_t ps_choice_count(void) {
  return static_cast<int32_t>(choice_infos().size());
}

PS_API int32_t ps_choice_info_get(int32_t index, ps_choice_info* out) {
  return guarded(nullptr, "ps_choice_info_get", [&] {
    require(out, "out");
    const auto n = static_cast<int32_t>(choice_infos().size());
    if (index < 0 || index >= n)
      api_fail(PS_ERROR_OUT_OF_RANGE, "option " + std::to_string(index) + " does not exist (0 to " +
                                          std::to_string(n - 1) + ")");
    *out = choice_infos()[index];
  });
}

PS_API int32_t ps_sim_set_choice(ps_sim* sim, const char* name, const char* value) {
  return guarded(error_slot(sim), "ps_sim_set_choice", [&] {
    require_idle(sim);
    require(name, "name");
    require(value, "value");
    Scene scene = sim->scene;
    set_scene_choice(scene, name, value);
    apply_scene(*sim, std::move(scene));
  });
}

PS_API int32_t ps_sim_get_choice(const ps_sim* sim, const char* name, const char** out) {
  return guarded(error_slot(sim), "ps_sim_get_choice", [&] {
    require_idle(sim);
    require(name, "name");
    require(out, "out");
    *out = scene_choice(sim->scene, name).c_str();
  });
}

}  // extern "C"
