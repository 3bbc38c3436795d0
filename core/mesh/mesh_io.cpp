// The only translation unit that includes CGAL's IO headers (they are slow to compile).
#include "mesh/mesh_io.hpp"

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <sstream>
#include <vector>

#include "common/error.hpp"
#include "mesh/off_reader.hpp"

namespace progsim {
namespace {

using CgalPoint = CGAL::Simple_cartesian<double>::Point_3;
using Polygons = std::vector<std::vector<std::size_t>>;

/// A point read from OBJ text. Unlike CGAL's point, it accepts "nan" and "inf", so that
/// such vertices reach validate_mesh, which names them, instead of failing the parse.
struct ObjPoint {
  double xyz[3];

  double operator[](int k) const { return xyz[k]; }

  friend std::istream& operator>>(std::istream& is, ObjPoint& p) {
    for (double& x : p.xyz) {
      std::string token;
      is >> token;
      const char* first = token.data() + (!token.empty() && token[0] == '+');
      const char* last = token.data() + token.size();
      const auto [end, error] = std::from_chars(first, last, x);
      if (token.empty() || error != std::errc() || end != last) is.setstate(std::ios::failbit);
    }
    return is;
  }
};

enum class Format { obj, off, ply };

/// The format named by the extension of `path` (any letter case); io_error otherwise.
Format format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return Format::obj;
  if (ext == ".off") return Format::off;
  if (ext == ".ply") return Format::ply;
  fail(Status::io_error, path + ": unknown mesh format '" + ext + "' (known: .obj, .off, .ply)");
}

/// Rejects a PLY "element NAME COUNT" line whose count is not a whole number the file can
/// hold: CGAL's reader casts "-1" to 2^64 − 1 items and loops over them for hours (found by
/// the fuzz target). Each item takes at least one byte. Returns the element's name (" " for
/// an element line without one, which still opens a block of properties).
std::string check_ply_element_count(const std::string& path, std::istringstream& words,
                                    std::uintmax_t file_size) {
  std::string name, count_text;
  words >> name >> count_text;
  std::uintmax_t count = 0;
  const auto [end, error] =
      std::from_chars(count_text.data(), count_text.data() + count_text.size(), count);
  if (error == std::errc() && end == count_text.data() + count_text.size() && count <= file_size)
    return name.empty() ? " " : name;
  fail(Status::io_error, path + ": cannot parse the file as PLY (element '" + name + "' declares " +
                             (count_text.empty() ? "no" : "'" + count_text + "'") +
                             " items, not a count the file's " + std::to_string(file_size) +
                             " bytes can hold)");
}

/// Rejects a "property list COUNT ITEM NAME" line whose COUNT type is wider than 16 bits: CGAL
/// resizes the list to whatever count the file gives before reading its items, so one face
/// claiming 2^31 − 1 indices allocates 8 GB (found by the fuzz target). Writers use uchar.
void check_ply_list_count_type(const std::string& path, std::istringstream& words) {
  std::string count_type;
  words >> count_type;
  for (const char* narrow :
       {"char", "uchar", "int8", "uint8", "short", "ushort", "int16", "uint16"})
    if (count_type == narrow) return;
  fail(Status::io_error, path +
                             ": cannot parse the file as PLY (a list property counts its items "
                             "with type '" +
                             count_type + "'; progsim reads 8- or 16-bit counts, such as uchar)");
}

/// CGAL reads vertex coordinates assuming a float or double property and dereferences a null
/// pointer for any other type (PLY_reader.h, found by the fuzz target): reject those first.
/// List properties are checked by check_ply_list_count_type.
void check_ply_property(const std::string& path, const std::string& element,
                        std::istringstream& words) {
  std::string type, name;
  words >> type;
  if (type == "list") return check_ply_list_count_type(path, words);
  words >> name;
  if (element != "vertex" || (name != "x" && name != "y" && name != "z")) return;
  if (type == "float" || type == "float32" || type == "double" || type == "float64") return;
  fail(Status::io_error, path + ": cannot parse the file as PLY (vertex property '" + name +
                             "' has type '" + type + "'; coordinates must be float or double)");
}

/// Checks a PLY header before CGAL reads it. CGAL dereferences the last element when it meets
/// a "property" line, and crashes if no "element" line came before; element counts and
/// property types are checked by the functions above.
void check_ply_header(const std::string& path) {
  std::error_code size_error;
  const std::uintmax_t file_size = std::filesystem::file_size(path, size_error);
  if (size_error) return;  // unreadable: the reader reports it
  std::ifstream in(path, std::ios::binary);
  std::string element;  // the element whose properties follow; "" before the first
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header") return;
    if (keyword == "element") {
      element = check_ply_element_count(path, words, file_size);
    }
    if (keyword == "property" && element.empty())
      fail(Status::io_error, path +
                                 ": cannot parse the file as PLY (a property comes before "
                                 "any element in the header)");
    if (keyword == "property") check_ply_property(path, element, words);
  }
}

/// Rejects headers that would make CGAL's readers misbehave instead of failing cleanly.
void check_header(const std::string& path, Format format) {
  if (format == Format::ply) check_ply_header(path);
}

/// What a parse failure means, for the message.
std::string parse_failure(Format format) {
  switch (format) {
    case Format::obj:
      return "cannot parse the file as OBJ (malformed or truncated)";
    case Format::off:
      return "cannot parse the file as OFF";
    case Format::ply:
      return "cannot parse the file as PLY (malformed or truncated)";
  }
  return "cannot parse the file";
}

/// Copies CGAL-side points (anything with p[0..2]) into a (|V| × 3) array.
template <class Point>
Positions to_positions(const std::vector<Point>& points) {
  Positions vertices(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices(i, k) = points[i][k];
  return vertices;
}

/// Reads OFF with read_off, OBJ and PLY with CGAL. Returns false on a parse failure; `soup`
/// then holds what was read so far.
bool read_soup(const std::string& path, Format format, PolygonSoup& soup) {
  if (format == Format::off) {
    soup = read_off(path);
    return true;
  }
  // CGAL's PLY reader would print to std::cerr by default.
  const auto quiet = CGAL::parameters::verbose(false);
  if (format == Format::obj) {
    std::vector<ObjPoint> points;
    const bool ok = CGAL::IO::read_OBJ(path, points, soup.polygons, quiet);
    soup.vertices = to_positions(points);
    return ok;
  }
  std::vector<CgalPoint> points;
  const bool ok = CGAL::IO::read_polygon_soup(path, points, soup.polygons, quiet);
  soup.vertices = to_positions(points);
  return ok;
}

/// invalid_mesh if a polygon references a vertex that does not exist.
void check_index_range(const std::string& path, const PolygonSoup& soup) {
  const std::size_t n = soup.vertices.rows();
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    for (const std::size_t v : soup.polygons[f]) {
      if (v < n) continue;
      // Negative indices in the file wrap around to huge unsigned values: print them signed.
      fail(Status::invalid_mesh, path + ": face " + std::to_string(f) + " references vertex " +
                                     std::to_string(static_cast<long long>(v)) +
                                     " (counting from 0), but the file has " + std::to_string(n) +
                                     " vertices");
    }
  }
}

/// invalid_mesh for polygons that are not triangles or meshes too large for int indices.
void check_triangles(const std::string& path, const PolygonSoup& soup) {
  if (soup.vertices.rows() > INT_MAX || soup.polygons.size() > INT_MAX)
    fail(Status::invalid_mesh,
         path + ": more than " + std::to_string(INT_MAX) + " vertices or faces");
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    const std::size_t n = soup.polygons[f].size();
    if (n == 3) continue;
    fail(Status::invalid_mesh, path + ": face " + std::to_string(f) + " has " + std::to_string(n) +
                                   " vertices, but progsim needs triangles (triangulate it)");
  }
}

Faces to_faces(const Polygons& polygons) {
  Faces faces(polygons.size(), 3);
  for (std::size_t f = 0; f < polygons.size(); ++f)
    for (int k = 0; k < 3; ++k) faces(f, k) = static_cast<int>(polygons[f][k]);
  return faces;
}

}  // namespace

TriangleMesh read_mesh(const std::string& path) {
  const Format format = format_of(path);
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    fail(Status::io_error, path + ": no such file (or not a regular file)");
  if (!std::ifstream(path)) fail(Status::io_error, path + ": cannot open the file for reading");
  check_header(path, format);
  PolygonSoup soup;
  bool ok = false;
  try {
    ok = read_soup(path, format, soup);
  } catch (const Error&) {  // read_off's own errors name the line already
    throw;
  } catch (const std::exception& e) {  // CGAL assertions, allocation failures
    fail(Status::io_error, path + ": " + parse_failure(format) + ": " + e.what());
  }
  // CGAL's OBJ reader rejects some out-of-range indices itself, after reading everything:
  // name the face even then.
  check_index_range(path, soup);
  if (!ok) fail(Status::io_error, path + ": " + parse_failure(format));
  check_triangles(path, soup);
  return TriangleMesh{soup.vertices, to_faces(soup.polygons)};
}

void write_mesh(const std::string& path, const TriangleMesh& mesh) {
  format_of(path);  // rejects unknown extensions before CGAL guesses
  std::vector<CgalPoint> points;
  points.reserve(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    points.emplace_back(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
  Polygons polygons(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f)
    polygons[f].assign(mesh.faces.row(f).data(), mesh.faces.row(f).data() + 3);
  bool ok = false;
  try {
    ok = CGAL::IO::write_polygon_soup(path, points, polygons,
                                      CGAL::parameters::stream_precision(17));
  } catch (const std::exception& e) {
    fail(Status::io_error, path + ": cannot write the file (" + e.what() + ")");
  }
  if (!ok) fail(Status::io_error, path + ": cannot write the file");
}

}  // namespace progsim
