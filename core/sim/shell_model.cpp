#include "sim/shell_model.hpp"

#include "energy/lumped_mass.hpp"

namespace progsim {

ShellModel build_shell_model(const Scene& scene) {
  ShellModel model;
  model.vertex_offset.push_back(0);
  model.face_offset.push_back(0);
  std::vector<const TriangleMesh*> meshes;
  for (const Body& body : scene.bodies) {
    model.vertex_offset.push_back(model.vertex_offset.back() + body.mesh.num_vertices());
    model.face_offset.push_back(model.face_offset.back() + body.mesh.num_faces());
    model.face_materials.insert(model.face_materials.end(), body.mesh.num_faces(), body.material);
    meshes.push_back(&body.mesh);
  }
  model.rest = merge_meshes(meshes);
  model.vertex_masses =
      lumped_vertex_masses(model.rest.vertices, model.rest.faces, model.face_materials);
  model.topology = build_topology(model.rest.faces, model.rest.num_vertices());
  return model;
}

}  // namespace progsim
