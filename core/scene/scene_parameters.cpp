#include "scene/scene_parameters.hpp"

#include <cmath>
#include <functional>
#include <vector>

#include "common/error.hpp"
#include "scene/parameter_table.hpp"

namespace progsim {
namespace {

/// Where a named parameter lives in a scene: one slot per body for material.* and pressure.
struct Accessor {
  const char* name;
  std::function<std::vector<double*>(Scene&)> slots;
};

std::vector<double*> material_slots(Scene& scene, double ShellMaterial::*field) {
  std::vector<double*> slots;
  for (Body& body : scene.bodies) slots.push_back(&(body.material.*field));
  return slots;
}

const std::vector<Accessor>& accessors() {
  static const std::vector<Accessor> table = {
      {"simulation.time_step", [](Scene& s) { return std::vector<double*>{&s.time_step}; }},
      {"simulation.duration", [](Scene& s) { return std::vector<double*>{&s.duration}; }},
      {"solver.newton_tolerance",
       [](Scene& s) { return std::vector<double*>{&s.solver.tolerance}; }},
      {"material.youngs_modulus",
       [](Scene& s) { return material_slots(s, &ShellMaterial::youngs_modulus); }},
      {"material.poisson_ratio",
       [](Scene& s) { return material_slots(s, &ShellMaterial::poisson_ratio); }},
      {"material.thickness", [](Scene& s) { return material_slots(s, &ShellMaterial::thickness); }},
      {"material.density", [](Scene& s) { return material_slots(s, &ShellMaterial::density); }},
      {"material.friction", [](Scene& s) { return material_slots(s, &ShellMaterial::friction); }},
      {"material.strain_limit",
       [](Scene& s) { return material_slots(s, &ShellMaterial::strain_limit); }},
      {"contact.dhat", [](Scene& s) { return std::vector<double*>{&s.contact.dhat}; }},
      {"contact.stiffness", [](Scene& s) { return std::vector<double*>{&s.contact.stiffness}; }},
      {"contact.friction_velocity",
       [](Scene& s) { return std::vector<double*>{&s.contact.friction_velocity}; }},
      {"gravity.x", [](Scene& s) { return std::vector<double*>{&s.gravity.x()}; }},
      {"gravity.y", [](Scene& s) { return std::vector<double*>{&s.gravity.y()}; }},
      {"gravity.z", [](Scene& s) { return std::vector<double*>{&s.gravity.z()}; }},
      {"pressure",
       [](Scene& s) {
         std::vector<double*> slots;
         for (Body& body : s.bodies) slots.push_back(&body.pressure);
         return slots;
       }},
  };
  return table;
}

/// The integer parameters: one slot each.
struct IntegerAccessor {
  const char* name;
  int& (*slot)(Scene&);
};

const std::vector<IntegerAccessor>& integer_accessors() {
  static const std::vector<IntegerAccessor> table = {
      {"simulation.output_every", [](Scene& s) -> int& { return s.output_every; }},
      {"solver.max_newton_iterations", [](Scene& s) -> int& { return s.solver.max_iterations; }},
      {"solver.max_cg_iterations", [](Scene& s) -> int& { return s.solver.max_cg_iterations; }},
  };
  return table;
}

const IntegerAccessor* integer_accessor(const std::string& name) {
  for (const IntegerAccessor& a : integer_accessors())
    if (name == a.name) return &a;
  return nullptr;
}

std::string known_names() {
  std::string names;
  for (const Accessor& a : accessors()) names += std::string(names.empty() ? "" : ", ") + a.name;
  for (const IntegerAccessor& a : integer_accessors()) names += std::string(", ") + a.name;
  return names;
}

[[noreturn]] void unknown(const std::string& name) {
  fail(Status::invalid_argument,
       "unknown parameter '" + name + "'; known parameters: " + known_names());
}

/// The table entry for a "group.name" parameter, or nullptr for gravity/pressure.
const ParameterSpec* spec_of(const std::string& name) {
  for (const ParameterSpec& spec : parameter_table())
    if (name == std::string(spec.group) + "." + spec.name) return &spec;
  return nullptr;
}

void check_value(const std::string& name, double value) {
  if (const ParameterSpec* spec = spec_of(name)) {
    try {
      check_parameter(*spec, value, name);
    } catch (const Error& e) {
      fail(Status::invalid_argument, e.what());
    }
  } else if (!std::isfinite(value)) {
    fail(Status::invalid_argument, name + " = " + std::to_string(value) + " must be finite");
  }
}

}  // namespace

void set_scene_parameter(Scene& scene, const std::string& name, double value) {
  if (const IntegerAccessor* a = integer_accessor(name)) {
    check_value(name, value);
    a->slot(scene) = static_cast<int>(value);
    return;
  }
  for (const Accessor& a : accessors())
    if (name == a.name) {
      check_value(name, value);
      for (double* slot : a.slots(scene)) *slot = value;
      return;
    }
  unknown(name);
}

double scene_parameter(const Scene& scene, const std::string& name) {
  Scene& mutable_scene = const_cast<Scene&>(scene);  // slots are only read below
  if (const IntegerAccessor* a = integer_accessor(name)) return a->slot(mutable_scene);
  for (const Accessor& a : accessors())
    if (name == a.name) {
      const std::vector<double*> slots = a.slots(mutable_scene);
      if (slots.empty()) fail(Status::out_of_range, "the scene has no bodies to read " + name);
      return *slots.front();
    }
  unknown(name);
}

}  // namespace progsim
