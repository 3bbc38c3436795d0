#include "sim/shell_model.hpp"

#include "energy/lumped_mass.hpp"

namespace progsim {

ShellModel build_shell_model(const Scene& scene) {
  ShellModel model;
  model.vertex_offset.push_back(0);
  model.face_offset.push_back(0);
  for (const Body& body : scene.bodies) {
    model.vertex_offset.push_back(model.vertex_offset.back() + body.mesh.num_vertices());
    model.face_offset.push_back(model.face_offset.back() + body.mesh.num_faces());
  }
  model.rest.vertices.resize(model.vertex_offset.back(), 3);
  model.rest.faces.resize(model.face_offset.back(), 3);
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const TriangleMesh& mesh = scene.bodies[b].mesh;
    model.rest.vertices.middleRows(model.vertex_offset[b], mesh.num_vertices()) = mesh.vertices;
    model.rest.faces.middleRows(model.face_offset[b], mesh.num_faces()) =
        mesh.faces.array() + model.vertex_offset[b];
    model.face_materials.insert(model.face_materials.end(), mesh.num_faces(),
                                scene.bodies[b].material);
  }
  model.vertex_masses =
      lumped_vertex_masses(model.rest.vertices, model.rest.faces, model.face_materials);
  model.topology = build_topology(model.rest.faces, model.rest.num_vertices());
  return model;
}

}  // namespace progsim
