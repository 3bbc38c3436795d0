#include "sim/start_separation.hpp"

#include <sstream>

#include "common/error.hpp"
#include "sim/contact_setup.hpp"
#include "sim/obstacle_script.hpp"
#include "sim/shell_model.hpp"

namespace progsim {
namespace {

/// "shell face f (vertices a, b, c)" in the input's vertex ids, or "obstacle face f".
std::string face_text(const CollisionMesh& mesh, int f, const std::vector<int>& input_vertex) {
  if (f >= mesh.num_shell_faces) return describe_face(mesh, f);
  std::ostringstream s;
  s << describe_face(mesh, f) << " (" << (input_vertex.empty() ? "" : "input ") << "vertices ";
  for (int k = 0; k < 3; ++k) {
    const int v = mesh.faces(f, k);
    s << (k ? ", " : "") << (input_vertex.empty() ? v : input_vertex[v]);
  }
  s << ')';
  return s.str();
}

/// The contact term of the scene's finest shell at rest with its obstacles at t = 0.
struct InputContact {
  ShellModel model;
  ObstacleScript obstacles;
  std::unique_ptr<ContactPotential> contact;
  explicit InputContact(const Scene& scene)
      : model(build_shell_model(scene)),
        obstacles(scene),
        contact(make_contact_potential(scene, model, obstacles)) {
    contact->set_obstacle_positions(obstacles.at(0.0));
  }
  Vector rest() const { return as_dofs(model.rest.vertices); }
};

}  // namespace

std::vector<FacePair> crossing_faces(const ContactPotential& contact, const Vector& x,
                                     std::size_t max_pairs) {
  Positions all(contact.mesh().num_vertices(), 3);
  all.topRows(contact.mesh().num_shell_vertices) = as_positions(x);
  all.bottomRows(contact.mesh().num_obstacle_vertices) = contact.obstacle_positions();
  return intersecting_faces(all, contact.mesh().faces, max_pairs);
}

void check_crossing_free(const ContactPotential& contact, const Vector& x, const std::string& label,
                         const std::vector<int>& input_vertex) {
  const auto crossing = crossing_faces(contact, x, 1);
  if (crossing.empty()) return;
  fail(Status::intersecting, label + ": " + face_text(contact.mesh(), crossing[0].a, input_vertex) +
                                 " and " + face_text(contact.mesh(), crossing[0].b, input_vertex) +
                                 " cross");
}

void check_input_contact_free(const Scene& scene) {
  if (!scene.effects.has(Effect::contact)) return;
  InputContact input(scene);
  const Vector x = input.rest();
  const std::string label = scene.name + ": the input mesh";
  check_crossing_free(*input.contact, x, label);
  try {
    input.contact->check_separated(x);
  } catch (const Error& e) {
    fail(Status::intersecting, label + ": " + e.what());
  }
}

std::size_t input_crossing_pairs(const Scene& scene) {
  const InputContact input(scene);
  return crossing_faces(*input.contact, input.rest(), 0).size();
}

}  // namespace progsim
