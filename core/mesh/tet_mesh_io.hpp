#pragma once
/// @file Reading tet meshes by file extension, and writing them as Medit .mesh or legacy VTK.
/// The boundary surface (tet_boundary.hpp) is written as OBJ, OFF or PLY with write_mesh().
#include <string>

#include "mesh/tet_mesh.hpp"

namespace progsim {

/// Whether `path` names a tet mesh file read_tet_mesh() reads (.mesh, .msh, .node, .ele, any
/// letter case), as opposed to a triangle surface.
bool is_tet_mesh_path(const std::string& path);

/// Reads a tet mesh, the format chosen by the extension of `path` (any letter case): .mesh
/// (read_medit), .msh (read_gmsh), .node or .ele (read_tetgen on the pair of files that share
/// the stem). The result is not validated: call validate_tet_mesh().
/// Throws Error(Status::io_error) for an unknown extension and what the readers throw.
TetMesh read_tet_mesh(const std::string& path);

/// Writes `mesh` as an ASCII Medit .mesh file (MeshVersionFormatted 2, Dimension 3, Vertices,
/// Tetrahedra with 1-based indices and reference 0, End), coordinates with 17 significant
/// digits so that read_medit gives back the same doubles. Written to `path` + ".partial" and
/// renamed, so a failure never leaves a half-written file. Throws Error(Status::io_error).
void write_tet_mesh_medit(const std::string& path, const TetMesh& mesh);

/// Writes `mesh` as a legacy ASCII VTK file (version 3.0): an UNSTRUCTURED_GRID with POINTS
/// (double, 17 significant digits), CELLS "4 i j k l" and CELL_TYPES 10 (VTK_TETRA, whose
/// orientation convention is progsim's). Written to `path` + ".partial" and renamed, so a
/// failure never leaves a half-written file. Throws Error(Status::io_error).
void write_tet_mesh_vtk(const std::string& path, const TetMesh& mesh);

}  // namespace progsim
