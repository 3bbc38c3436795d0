#include "sim/contact_setup.hpp"

#include <algorithm>
#include <cmath>

namespace progsim {
namespace {

/// Per shell vertex: the largest value of a face property over its incident faces.
std::vector<double> vertex_max_of_faces(const ShellModel& model,
                                        double (*property)(const ShellMaterial&)) {
  std::vector<double> out(model.rest.num_vertices(), 0.0);
  for (int f = 0; f < model.rest.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      double& slot = out[model.rest.faces(f, k)];
      slot = std::max(slot, property(model.face_materials[f]));
    }
  return out;
}

double half_thickness(const ShellMaterial& m) {
  return 0.5 * m.thickness;
}
double friction_of(const ShellMaterial& m) {
  return m.friction;
}

/// The force a contact must resist (see make_contact_potential).
double reference_force(const Scene& scene, const ShellModel& model) {
  const double mass = model.vertex_masses.mean();
  double force = mass * scene.gravity.norm();
  if (scene.mode == StepMode::dynamic)
    force = std::max(force, mass * scene.contact.dhat / (scene.time_step * scene.time_step));
  const double edge = bounding_box_diagonal(model.rest.vertices) /
                      std::sqrt(static_cast<double>(model.rest.num_vertices()));
  for (const ShellMaterial& m : model.face_materials)  // stretching an edge by 0.1%
    force = std::max(force, 1e-3 * m.youngs_modulus * m.thickness * edge);
  for (const SolidMaterial& m : model.tet_materials)  // the same for a solid's edge-sized cell
    force = std::max(force, 1e-3 * m.youngs_modulus * edge * edge);
  return force;
}

}  // namespace

std::vector<double> shell_contact_offsets(const ShellModel& model) {
  return vertex_max_of_faces(model, half_thickness);
}

std::unique_ptr<ContactPotential> make_contact_potential(const Scene& scene,
                                                         const ShellModel& model,
                                                         const ObstacleScript& obstacles) {
  CollisionMesh mesh =
      build_collision_mesh(model.rest.vertices, model.rest.faces, shell_contact_offsets(model),
                           vertex_max_of_faces(model, friction_of), obstacles.surfaces());
  std::optional<GroundPlane> ground;
  if (scene.ground.enabled)
    ground = GroundPlane{scene.ground.normal, scene.ground.height, scene.ground.friction};
  double stiffness = scene.contact.stiffness;
  if (stiffness == 0.0)
    stiffness = ContactPotential::stiffness_for_force(reference_force(scene, model),
                                                      scene.contact.dhat, 2.0 * mesh.max_offset());
  return std::make_unique<ContactPotential>(std::move(mesh), scene.contact.dhat, stiffness, ground);
}

std::unique_ptr<FrictionPotential> make_friction_potential(const Scene& scene,
                                                           const ContactPotential& contact) {
  // Every pair involves the shell and mixes μ = √(μ_a μ_b): a smooth shell has no friction.
  const std::vector<double>& mu = contact.mesh().vertex_friction;
  if (std::none_of(mu.begin(), mu.begin() + contact.mesh().num_shell_vertices,
                   [](double m) { return m > 0.0; }))
    return nullptr;
  return std::make_unique<FrictionPotential>(
      contact, scene.contact.friction_velocity * scene.time_step);  // ε_x = ε_v h (IPC §5)
}

LimitedFaces limited_faces(const ShellModel& model) {
  LimitedFaces out;
  out.faces.resize(model.rest.num_faces(), 3);
  double min_excess = std::numeric_limits<double>::infinity();
  for (int f = 0; f < model.rest.num_faces(); ++f) {
    const ShellMaterial& m = model.face_materials[f];
    if (m.strain_limit == 0.0) continue;
    out.faces.row(static_cast<Eigen::Index>(out.limits.size())) = model.rest.faces.row(f);
    out.limits.push_back(m.strain_limit);
    out.stiffness = std::max(out.stiffness, m.youngs_modulus * m.thickness);
    min_excess = std::min(min_excess, m.strain_limit - 1.0);
  }
  out.faces.conservativeResize(static_cast<Eigen::Index>(out.limits.size()), 3);
  if (!out.limits.empty()) out.band = 0.5 * min_excess;
  return out;
}

std::unique_ptr<StrainLimit> make_strain_limit(const ShellModel& model) {
  LimitedFaces limited = limited_faces(model);
  if (limited.limits.empty()) return nullptr;
  return std::make_unique<StrainLimit>(model.rest.vertices, limited.faces,
                                       std::move(limited.limits), limited.band, limited.stiffness);
}

}  // namespace progsim
