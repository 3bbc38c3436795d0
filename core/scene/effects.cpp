#include "scene/effects.hpp"

#include "common/error.hpp"

namespace progsim {

const char* effect_name(Effect e) {
  switch (e) {
    case Effect::membrane:
      return "membrane";
    case Effect::bending:
      return "bending";
    case Effect::gravity:
      return "gravity";
    case Effect::pressure:
      return "pressure";
    case Effect::contact:
      return "contact";
    case Effect::friction:
      return "friction";
    case Effect::strain_limit:
      return "strain_limit";
    case Effect::wind:
      return "wind";
    case Effect::elasticity:
      return "elasticity";
    case Effect::count_:
      break;
  }
  return "unknown";
}

Effect parse_effect(const std::string& name) {
  std::string known;
  for (unsigned i = 0; i < static_cast<unsigned>(Effect::count_); ++i) {
    const Effect e = static_cast<Effect>(i);
    if (name == effect_name(e)) return e;
    known += std::string(known.empty() ? "" : ", ") + effect_name(e);
  }
  fail(Status::invalid_scene, "unknown effect '" + name + "' (known effects: " + known + ")");
}

std::vector<std::string> effect_names(const EffectSet& effects) {
  std::vector<std::string> names;
  for (unsigned i = 0; i < static_cast<unsigned>(Effect::count_); ++i)
    if (effects.has(static_cast<Effect>(i)))
      names.emplace_back(effect_name(static_cast<Effect>(i)));
  return names;
}

}  // namespace progsim
