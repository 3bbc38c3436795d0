#pragma once
/// @file The physical effects a scene can enable. Only enabled effects get an energy term.
#include <string>
#include <vector>

namespace progsim {

/// A physical effect. Each maps to (at most) one energy term.
enum class Effect : unsigned {
  membrane = 0,  ///< Neo-Hookean membrane stretching
  bending,       ///< discrete hinge bending
  gravity,       ///< uniform gravitational acceleration
  pressure,      ///< uniform pressure on closed bodies (balloons)
  contact,       ///< IPC barrier contact (self, between bodies, obstacles, ground) with CCD
  friction,      ///< lagged smoothed Coulomb friction on contacts (needs contact; μ > 0)
  strain_limit,  ///< barrier on membrane stretches above material.strain_limit
  wind,          ///< aerodynamic drag and lift of a wind on every face (dynamic scenes)
  elasticity,    ///< hyperelastic energy of the tets of volumetric bodies (VPD §3.1.3)
  count_,
};

/// A set of effects.
class EffectSet {
 public:
  void enable(Effect e) { bits_ |= 1u << static_cast<unsigned>(e); }
  void disable(Effect e) { bits_ &= ~(1u << static_cast<unsigned>(e)); }
  bool has(Effect e) const { return (bits_ >> static_cast<unsigned>(e)) & 1u; }

 private:
  unsigned bits_ = 0;
};

/// Stable name of an effect ("membrane", ...).
const char* effect_name(Effect e);

/// The effect with the given name. Throws Error(invalid_scene) listing the known names.
Effect parse_effect(const std::string& name);

/// The names of the enabled effects, in enum order.
std::vector<std::string> effect_names(const EffectSet& effects);

}  // namespace progsim
