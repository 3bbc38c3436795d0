#pragma once
/// @file A strict reader of text OFF files (Geomview's Object File Format).
///
/// progsim reads OFF itself instead of through CGAL: CGAL's OFF scanner has undefined behaviour
/// on malformed headers and indices (three separate findings of our fuzz target), and patching
/// its input with pre-checks did not end the series. This reader validates every token before
/// it allocates or indexes anything.
#include <cstddef>
#include <string>
#include <vector>

#include "mesh/triangle_mesh.hpp"

namespace progsim {

/// Vertices and polygons as a file lists them, before the triangle check.
struct PolygonSoup {
  Positions vertices;                              ///< |V| × 3
  std::vector<std::vector<std::size_t>> polygons;  ///< vertex indices, each in [0, |V|)
};

/// Reads the text OFF file at `path`: a keyword `[ST][C][N]OFF`, the counts "|V| |F| [|E|]",
/// |V| vertex lines starting with x y z, then |F| face lines "k i₁ … i_k". Extra values on a
/// line (normals, colours, texture coordinates) are ignored, as is the edge count; "#" starts a
/// comment. "nan" and "inf" coordinates are read, so that validate_mesh names them.
/// Throws Error(Status::io_error) for binary, 4D or nD OFF, a missing keyword, counts that are
/// not whole numbers or that the file is too short to hold, malformed numbers and truncated
/// files; Error(Status::invalid_mesh) for a face size or index that is not a whole number in
/// range. Messages start with the path and name the line (counting from 1).
PolygonSoup read_off(const std::string& path);

}  // namespace progsim
