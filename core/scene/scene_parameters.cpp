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

/// Every body's field: one value for all. In a scene that mixes shells and solids a value would
/// cross kinds (a cloth's modulus onto a jelly), so there it is refused.
std::vector<double*> material_slots(Scene& scene, double ShellMaterial::*field) {
  if (mixes_shells_and_solids(scene))
    fail(Status::unsupported,
         "material parameters set one value on every body, and this scene mixes shells and "
         "volumetric (tet) bodies: set each body's material in the scene");
  std::vector<double*> slots;
  for (Body& body : scene.bodies) slots.push_back(&(body.material.*field));
  return slots;
}

const std::vector<Accessor>& accessors() {
  static const std::vector<Accessor> table = {
      {"simulation.time_step", [](Scene& s) { return std::vector<double*>{&s.time_step}; }},
      {"simulation.duration", [](Scene& s) { return std::vector<double*>{&s.duration}; }},
      {"simulation.gravity_ramp", [](Scene& s) { return std::vector<double*>{&s.gravity_ramp}; }},
      {"solver.newton_tolerance",
       [](Scene& s) { return std::vector<double*>{&s.solver.tolerance}; }},
      {"material.youngs_modulus",
       [](Scene& s) { return material_slots(s, &ShellMaterial::youngs_modulus); }},
      {"material.bending_youngs_modulus",
       [](Scene& s) { return material_slots(s, &ShellMaterial::bending_youngs_modulus); }},
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
      {"progressive.consistency_weight",
       [](Scene& s) { return std::vector<double*>{&s.progressive.consistency_weight}; }},
      {"progressive.preview_tolerance",
       [](Scene& s) { return std::vector<double*>{&s.progressive.preview_tolerance}; }},
      {"progressive.galerkin_refresh",
       [](Scene& s) { return std::vector<double*>{&s.progressive.galerkin_refresh}; }},
      {"wind.density", [](Scene& s) { return std::vector<double*>{&s.wind.density}; }},
      {"wind.drag", [](Scene& s) { return std::vector<double*>{&s.wind.drag}; }},
      {"wind.lift", [](Scene& s) { return std::vector<double*>{&s.wind.lift}; }},
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

/// The integer parameters (a switch is 0 or 1): one slot each, read and written as doubles.
struct IntegerAccessor {
  const char* name;
  double (*get)(const Scene&);
  void (*set)(Scene&, double);
};

const std::vector<IntegerAccessor>& integer_accessors() {
  static const std::vector<IntegerAccessor> table = {
      {"simulation.output_every", [](const Scene& s) { return double(s.output_every); },
       [](Scene& s, double v) { s.output_every = int(v); }},
      {"solver.max_newton_iterations",
       [](const Scene& s) { return double(s.solver.max_iterations); },
       [](Scene& s, double v) { s.solver.max_iterations = int(v); }},
      {"solver.max_cg_iterations",
       [](const Scene& s) { return double(s.solver.max_cg_iterations); },
       [](Scene& s, double v) { s.solver.max_cg_iterations = int(v); }},
      {"contact.crossing_start",
       [](const Scene& s) { return s.contact.crossing_start ? 1.0 : 0.0; },
       [](Scene& s, double v) { s.contact.crossing_start = v != 0.0; }},
      {"progressive.preview_iterations",
       [](const Scene& s) { return double(s.progressive.preview_iterations); },
       [](Scene& s, double v) { s.progressive.preview_iterations = int(v); }},
      {"progressive.proximal", [](const Scene& s) { return s.progressive.proximal ? 1.0 : 0.0; },
       [](Scene& s, double v) { s.progressive.proximal = v != 0.0; }},
      {"solver.line_search_extrapolation",
       [](const Scene& s) { return s.solver.extrapolate ? 1.0 : 0.0; },
       [](Scene& s, double v) { s.solver.extrapolate = v != 0.0; }},
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
    a->set(scene, value);
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
  if (const IntegerAccessor* a = integer_accessor(name)) return a->get(scene);
  Scene& mutable_scene = const_cast<Scene&>(scene);  // slots are only read below
  for (const Accessor& a : accessors())
    if (name == a.name) {
      const std::vector<double*> slots = a.slots(mutable_scene);
      if (slots.empty()) fail(Status::out_of_range, "the scene has no bodies to read " + name);
      return *slots.front();
    }
  unknown(name);
}

}  // namespace progsim
