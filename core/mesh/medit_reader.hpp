#pragma once
/// @file A strict reader of ASCII Medit .mesh files (tetrahedra).
#include <string>

#include "mesh/tet_mesh.hpp"

namespace progsim {

/// Reads the ASCII Medit file at `path` (format: INRIA's MEDIT file description, as libMeshb
/// of ISC Gamma writes it): `MeshVersionFormatted k`, an optional `Dimension 3`, then sections
/// `Keyword count` followed by count items, up to `End` or the end of the file. Items are read
/// as a stream of words, so line breaks are free. `Vertices` items are "x y z ref" and
/// `Tetrahedra` items "i j k l ref" with 1-based indices; references are ignored. The element,
/// requirement and normal sections of surface meshes (Triangles, Edges, Corners, Ridges,
/// Required*, Quadrilaterals, Hexahedra, Prisms, Normals, Tangents, ...) are skipped. "#"
/// starts a comment. "nan" and "inf" coordinates are read, so that validate_tet_mesh names them.
/// Does not validate the geometry: call validate_tet_mesh().
/// Throws Error(Status::io_error) for a missing header, a dimension other than 3, an unknown
/// keyword, a repeated section, counts that are not whole numbers or that the file is too short
/// to hold, malformed numbers and truncated files; Error(Status::invalid_mesh) for a tet index
/// out of range (or Tetrahedra before Vertices). Messages start with the path and name the line.
TetMesh read_medit(const std::string& path);

}  // namespace progsim
