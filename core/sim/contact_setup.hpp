#pragma once
/// @file Builds the contact, friction and strain-limit terms a scene enables, with their
/// parameters chosen from the scene (C-IPC, Li et al. 2021, §4–5; IPC, Li et al. 2020, §4.3).
#include <memory>

#include "contact/contact_potential.hpp"
#include "contact/friction_potential.hpp"
#include "energy/strain_limit.hpp"
#include "scene/scene.hpp"
#include "sim/obstacle_script.hpp"
#include "sim/shell_model.hpp"

namespace progsim {

/// Per shell vertex its contact offset ξ = t/2, the largest over the vertex's faces (C-IPC
/// codimensional thickness).
std::vector<double> shell_contact_offsets(const ShellModel& model);

/// The contact barrier over the shell, the obstacles and the ground. Each shell vertex gets the
/// offset ξ = t/2 of its body (C-IPC codimensional thickness), obstacles 0. κ is the scene's
/// contact.stiffness, or (0) the stiffness at which a pair at half the gap d̂ resists the
/// largest of: a vertex's weight, the force that stops it within d̂ in one step (dynamics),
/// and the force that stretches a typical edge by 0.1%. A small start keeps pairs that begin
/// inside d̂ from being kicked apart; κ then grows adaptively where gaps close (IPC §4.3).
std::unique_ptr<ContactPotential> make_contact_potential(const Scene& scene,
                                                         const ShellModel& model,
                                                         const ObstacleScript& obstacles);

/// Friction over the contact's pairs with slip threshold ε_v h, or nullptr when the shell's
/// μ is 0 everywhere (every pair then mixes to μ = 0, and friction costs nothing).
std::unique_ptr<FrictionPotential> make_friction_potential(const Scene& scene,
                                                           const ContactPotential& contact);

/// The faces whose material has a strain limit, and the parameters of their barrier.
struct LimitedFaces {
  Faces faces;                 ///< (k × 3) the limited faces, in the model's vertex indices
  std::vector<double> limits;  ///< s_max per limited face
  double band = 0.0;           ///< ŝ = half the smallest s_max − 1
  double stiffness = 0.0;      ///< κ = the largest E t over them (energy per area)
};
/// The model's limited faces (none: empty faces and limits).
LimitedFaces limited_faces(const ShellModel& model);

/// The strain-limit barrier over limited_faces(model), or nullptr if no face has a limit.
std::unique_ptr<StrainLimit> make_strain_limit(const ShellModel& model);

}  // namespace progsim
