#include "sim/shell_model.hpp"

#include "energy/lumped_mass.hpp"
#include "energy/tet_lumped_mass.hpp"

namespace progsim {

namespace {

/// A solid body's tets, renumbered into the merged model, with its material.
void append_tets(const Body& body, int first_vertex, ShellModel& model) {
  const Eigen::Index old = model.tets.rows();
  model.tets.conservativeResize(old + body.tets.rows(), 4);
  model.tets.bottomRows(body.tets.rows()) = body.tets.array() + first_vertex;
  model.tet_materials.insert(model.tet_materials.end(), body.tets.rows(), solid_material(body));
}

}  // namespace

ShellModel build_shell_model(const Scene& scene) {
  ShellModel model;
  model.vertex_offset.push_back(0);
  model.face_offset.push_back(0);
  std::vector<const TriangleMesh*> meshes;
  for (const Body& body : scene.bodies) {
    const int first_vertex = model.vertex_offset.back();
    model.vertex_offset.push_back(first_vertex + body.mesh.num_vertices());
    model.face_offset.push_back(model.face_offset.back() + body.mesh.num_faces());
    ShellMaterial surface = body.material;
    if (is_solid(body)) {  // a solid's boundary is no shell: no thickness, no strain limit
      surface.thickness = 0.0;
      surface.strain_limit = 0.0;
    }
    model.face_materials.insert(model.face_materials.end(), body.mesh.num_faces(), surface);
    meshes.push_back(&body.mesh);
    append_tets(body, first_vertex, model);
  }
  model.rest = merge_meshes(meshes);
  model.vertex_masses =
      lumped_vertex_masses(model.rest.vertices, model.rest.faces, model.face_materials) +
      lumped_tet_masses(model.rest.vertices, model.tets, model.tet_materials);
  model.topology = build_topology(model.rest.faces, model.rest.num_vertices());
  return model;
}

}  // namespace progsim
