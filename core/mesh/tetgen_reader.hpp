#pragma once
/// @file A strict reader of TetGen's .node and .ele file pairs.
#include <string>

#include "mesh/tet_mesh.hpp"

namespace progsim {

/// Reads the TetGen pair `node_path` and `ele_path` (format: the TetGen manual, §5.2 "Files
/// formats", .node and .ele). The .node file starts with "points 3 attributes markers" (markers
/// 0 or 1), then one line "index x y z [attributes] [marker]" per point; the first point's index
/// (0 or 1) sets the numbering of both files, and the others must follow it in sequence. The
/// .ele file starts with "tets nodes-per-tet attributes" (4 or 10 nodes per tet, of which the
/// first 4 are the corners), then one line "index n1 ... [attributes]" per tet. Attributes and
/// markers are ignored; "#" starts a comment; "nan" and "inf" coordinates are read, so that
/// validate_tet_mesh names them. Does not validate the geometry: call validate_tet_mesh().
/// Throws Error(Status::io_error) for malformed headers, counts that are not whole numbers or
/// that the file is too short to hold, malformed numbers, points out of sequence and truncated
/// files; Error(Status::invalid_mesh) for a tet index out of range. Messages start with the path
/// of the file at fault and name the line.
TetMesh read_tetgen(const std::string& node_path, const std::string& ele_path);

}  // namespace progsim
