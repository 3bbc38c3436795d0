#pragma once
/// @file A strict reader of ASCII Gmsh .msh files, versions 2.2 and 4.1 (tetrahedra).
#include <string>

#include "mesh/tet_mesh.hpp"

namespace progsim {

/// Reads the ASCII Gmsh file at `path` (format: the Gmsh reference manual, section "MSH file
/// format", versions 2.2 and 4.1): `$MeshFormat`, `$Nodes`, `$Elements`; other sections
/// ($PhysicalNames, $Entities, $NodeData, ...) are skipped up to their `$End...` line. Node tags
/// need not be contiguous (they are mapped to indices in the order the file lists the nodes).
/// Only 4-node tetrahedra (element type 4) are kept, in file order; points, lines, triangles
/// and other elements are skipped. "nan" and "inf" coordinates are read, so that
/// validate_tet_mesh names them. Does not validate the geometry: call validate_tet_mesh().
/// Throws Error(Status::io_error) for binary files (file-type 1), other versions, missing or
/// misplaced sections, counts that are not whole numbers or that the file is too short to hold,
/// malformed numbers and truncated files; Error(Status::invalid_mesh) for a repeated node tag
/// or a tet naming a node that $Nodes does not define. Messages start with the path and name
/// the line.
TetMesh read_gmsh(const std::string& path);

}  // namespace progsim
