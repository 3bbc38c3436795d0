#pragma once
/// @file The shell's own potentials a scene enables on one mesh: membrane, bending, gravity and
/// per-body pressure (PSQ §3.1, Ψ_l). Direct simulations add them to their problem; the
/// progressive proxy evaluates the finest level's through the prolongation.
#include <memory>
#include <utility>
#include <vector>

#include "energy/energy_term.hpp"
#include "scene/scene.hpp"
#include "sim/shell_model.hpp"

namespace progsim {

class Gravity;
class Pressure;

/// The terms, and which of them are pressures and gravity (to ramp the loads between steps).
struct ShellElastics {
  std::vector<std::unique_ptr<EnergyTerm>> terms;
  std::vector<std::pair<Pressure*, int>> pressures;  ///< (term owned by `terms`, body index)
  Gravity* gravity = nullptr;                        ///< owned by `terms`; null without gravity
};

/// Membrane (of the given model), bending and (with_gravity) gravity on `model`, and a pressure
/// term per body with a non-zero pressure, as the scene's effects enable. Pressures start at
/// 0 Pa.
ShellElastics make_shell_elastics(const Scene& scene, const ShellModel& model, bool with_gravity,
                                  MembraneModel membrane = MembraneModel::neo_hookean);

}  // namespace progsim
