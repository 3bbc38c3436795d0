#pragma once
/// @file Reading and writing triangle meshes in OBJ, OFF and PLY (CGAL's IO, except for
/// reading OFF: see off_reader.hpp).
#include <string>

#include "mesh/triangle_mesh.hpp"

namespace progsim {

/// Reads a mesh from an .obj, .off or .ply file (format from the extension). Polygons
/// with more than three vertices are an error (progsim simulates triangle meshes).
/// The result is not validated: call validate_mesh().
/// Throws Error(Status::io_error) if the file cannot be read or parsed,
/// Error(Status::invalid_mesh) if it holds non-triangle faces or out-of-range indices.
/// Messages start with the path and name the face. OBJ and OFF "nan"/"inf" coordinates are
/// read (and left to validate_mesh); in PLY (CGAL's parser) they are parse errors (io_error).
/// PLY coordinates must be float or double, and list properties must count their items in
/// 8 or 16 bits (uchar, as writers use; wider counts are an io_error).
TriangleMesh read_mesh(const std::string& path);

/// Writes a mesh to .obj, .off or .ply (format from the extension): text with 17 significant
/// digits for OBJ and OFF, binary PLY, so that reading it back gives the same doubles.
/// Throws Error(Status::io_error) on failure.
void write_mesh(const std::string& path, const TriangleMesh& mesh);

}  // namespace progsim
