#pragma once
/// @file The simulated shell: every body of a scene merged into one mesh with per-face
/// materials, lumped masses and adjacency. This is one level's geometry.
#include <vector>

#include "energy/shell_material.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh/triangle_mesh.hpp"
#include "scene/scene.hpp"

namespace progsim {

/// All bodies of a scene as one mesh. Body b owns vertices [vertex_offset[b], vertex_offset[b+1])
/// and faces [face_offset[b], face_offset[b+1]). Volumetric bodies add their tets; their faces
/// (their boundaries) carry a zero thickness: no shell mass, no contact offset.
struct ShellModel {
  TriangleMesh rest;                          ///< rest (and initial) shape, world space
  std::vector<ShellMaterial> face_materials;  ///< (|F|)
  std::vector<int> vertex_offset;             ///< (bodies + 1)
  std::vector<int> face_offset;               ///< (bodies + 1)
  Tets tets;                                  ///< (|T| × 4) of the volumetric bodies
  std::vector<SolidMaterial> tet_materials;   ///< (|T|)
  Eigen::VectorXd vertex_masses;              ///< lumped masses (|V|), kg: shells and tets
  MeshTopology topology;
};

/// Merges the scene's bodies. Precondition: validate_scene(scene) passed.
ShellModel build_shell_model(const Scene& scene);

}  // namespace progsim
