#include "scene/scene_choices.hpp"

#include <functional>

#include "common/error.hpp"
#include "scene/choice_table.hpp"

namespace progsim {
namespace {

/// Where a named option lives in a scene, as its enum's index.
struct ChoiceAccessor {
  const char* name;
  std::function<int(const Scene&)> get;
  std::function<void(Scene&, int)> set;
};

template <typename Enum>
ChoiceAccessor field(const char* name, Enum ProgressiveSettings::*member) {
  return {name, [member](const Scene& s) { return static_cast<int>(s.progressive.*member); },
          [member](Scene& s, int k) { s.progressive.*member = static_cast<Enum>(k); }};
}

const std::vector<ChoiceAccessor>& accessors() {
  static const std::vector<ChoiceAccessor> table = {
      {"simulation.mode", [](const Scene& s) { return static_cast<int>(s.mode); },
       [](Scene& s, int k) { s.mode = static_cast<StepMode>(k); }},
      {"material.bending_model",
       [](const Scene& s) {  // a scene without bodies reads the material default
         return static_cast<int>(s.bodies.empty() ? ShellMaterial{}.bending_model
                                                  : s.bodies.front().material.bending_model);
       },
       [](Scene& s, int k) {
         for (Body& body : s.bodies) body.material.bending_model = static_cast<BendingModel>(k);
       }},
      {"material.solid_model",
       [](const Scene& s) {
         return static_cast<int>(s.bodies.empty() ? Body{}.solid_model
                                                  : s.bodies.front().solid_model);
       },
       [](Scene& s, int k) {
         for (Body& body : s.bodies) body.solid_model = static_cast<SolidModel>(k);
       }},
      field("progressive.prolongation", &ProgressiveSettings::prolongation),
      field("progressive.proxy_hessian", &ProgressiveSettings::hessian),
      field("progressive.preview_membrane", &ProgressiveSettings::preview_membrane),
      field("progressive.prediction", &ProgressiveSettings::prediction),
  };
  return table;
}

/// The table row and accessor of `name` ("group.name").
std::pair<const ChoiceSpec*, const ChoiceAccessor*> lookup(const std::string& name) {
  const std::size_t dot = name.find('.');
  const ChoiceSpec& spec =
      find_choice(name.substr(0, dot), dot == std::string::npos ? "" : name.substr(dot + 1));
  for (const ChoiceAccessor& a : accessors())
    if (name == a.name) return {&spec, &a};
  fail(Status::internal, "the choice table's '" + name + "' has no scene accessor");
}

}  // namespace

void set_scene_choice(Scene& scene, const std::string& name, const std::string& value) {
  const auto [spec, accessor] = lookup(name);
  accessor->set(scene, choice_index(*spec, value, name, Status::invalid_argument));
}

const std::string& scene_choice(const Scene& scene, const std::string& name) {
  const auto [spec, accessor] = lookup(name);
  return spec->options.at(static_cast<std::size_t>(accessor->get(scene)));
}

}  // namespace progsim
