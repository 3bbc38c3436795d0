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
#include <limits>
#include <sstream>
#include <vector>

#include "common/error.hpp"

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

/// The next whitespace-separated token of an OFF file outside "#" comments ("" at the end).
std::string next_off_token(std::istream& in) {
  std::string token;
  while (in >> token) {
    if (token[0] != '#') return token;
    std::getline(in, token);
  }
  return "";
}

/// CGAL's OFF reader allocates the element counts of the header before reading any element,
/// so a corrupt header could claim gigabytes. Rejects counts that the file is too short to
/// hold: in text, a vertex takes at least 6 bytes ("0 0 0\n") and a face at least 2 ("0\n").
/// Binary OFF is refused; nOFF headers are left to CGAL.
void check_off_header_counts(const std::string& path) {
  std::ifstream in(path);
  const std::string keyword = next_off_token(in);
  if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0 || keyword[0] == 'n')
    return;
  const std::string vertices = next_off_token(in);
  // CGAL's binary OFF header parser overflows int on corrupt counts (found by the fuzzer). CGAL
  // reads the word as its leading letters and digits ("BINARY\x0f" is binary too).
  const auto word_end = std::find_if(vertices.begin(), vertices.end(), [](char c) {
    return !std::isalnum(static_cast<unsigned char>(c));
  });
  if (std::string(vertices.begin(), word_end) == "BINARY")
    fail(Status::io_error, path +
                               ": binary OFF is not supported; save the mesh as text OFF, "
                               "OBJ or PLY");
  const std::string faces = next_off_token(in);
  const std::string edges = next_off_token(in);
  std::uintmax_t nv = 0, nf = 0, ne = 0;
  if (std::from_chars(vertices.data(), vertices.data() + vertices.size(), nv).ec != std::errc() ||
      std::from_chars(faces.data(), faces.data() + faces.size(), nf).ec != std::errc())
    return;  // not a number: CGAL decides
  // The edge count is not used, but CGAL doubles it in an int (the fuzzer found the overflow).
  if (std::from_chars(edges.data(), edges.data() + edges.size(), ne).ec == std::errc() &&
      ne > static_cast<std::uintmax_t>(std::numeric_limits<int>::max() / 2))
    fail(Status::io_error, path + ": the header declares " + edges + " edges (corrupt header)");
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return;
  if (nv <= size / 6 && nf <= size / 2 && 6 * nv + 2 * nf <= size) return;
  fail(Status::io_error, path + ": the header declares " + std::to_string(nv) + " vertices and " +
                             std::to_string(nf) + " faces, more than the file's " +
                             std::to_string(size) +
                             " bytes can hold (truncated file or corrupt header)");
}

/// The non-empty lines of a text file with "#" comments removed.
std::vector<std::string> content_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  return lines;
}

/// CGAL's OFF scanner reads face indices as doubles and casts them to size_t, which is
/// undefined for negative or huge values (found by the fuzz target): check every index of a
/// text OFF file is a whole number in [0, |V|) first. Line layout: keyword, counts, |V| vertex
/// lines, then face lines "k i₁ … i_k [colour]". Layouts it does not know are left to CGAL.
void check_off_face_indices(const std::string& path) {
  const std::vector<std::string> lines = content_lines(path);
  if (lines.size() < 2) return;
  std::istringstream header(lines[0] + " " + lines[1]);
  std::string keyword;
  long long nv = 0, nf = 0;
  header >> keyword;
  if (keyword.find("OFF") == std::string::npos || keyword[0] == 'n' || !(header >> nv >> nf) ||
      nv < 0 || nf < 0)
    return;
  const std::size_t first_face = 2 + static_cast<std::size_t>(nv);
  for (std::size_t f = 0; f < static_cast<std::size_t>(nf) && first_face + f < lines.size(); ++f) {
    std::istringstream words(lines[first_face + f]);
    std::string token;
    long long k = 0;
    std::string count_text;
    words >> count_text;
    const auto [count_end, count_error] =
        std::from_chars(count_text.data(), count_text.data() + count_text.size(), k);
    if (count_error != std::errc() || count_end != count_text.data() + count_text.size() || k < 0)
      fail(Status::invalid_mesh, path + ": face " + std::to_string(f) + " has '" + count_text +
                                     "' vertices, not a whole number");
    for (long long i = 0; i < k && words >> token; ++i) {
      long long index = -1;
      const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), index);
      if (error == std::errc() && end == token.data() + token.size() && index >= 0 && index < nv)
        continue;
      fail(Status::invalid_mesh, path + ": face " + std::to_string(f) + " references vertex '" +
                                     token + "', not an index in [0, " + std::to_string(nv) + ")");
    }
  }
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

/// CGAL reads vertex coordinates assuming a float or double property and dereferences a null
/// pointer for any other type (PLY_reader.h, found by the fuzz target): reject those first.
void check_ply_coordinate_type(const std::string& path, const std::string& element,
                               std::istringstream& words) {
  std::string type, name;
  words >> type >> name;
  if (element != "vertex" || (name != "x" && name != "y" && name != "z")) return;
  if (type == "float" || type == "float32" || type == "double" || type == "float64") return;
  fail(Status::io_error, path + ": cannot parse the file as PLY (vertex property '" + name +
                             "' has type '" + type + "'; coordinates must be float or double)");
}

/// Checks a PLY header before CGAL reads it. CGAL dereferences the last element when it meets
/// a "property" line, and crashes if no "element" line came before; element counts and
/// coordinate types are checked by the functions above.
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
    if (keyword == "property") check_ply_coordinate_type(path, element, words);
  }
}

/// Rejects headers that would make CGAL's readers misbehave instead of failing cleanly.
void check_header(const std::string& path, Format format) {
  if (format == Format::off) {
    check_off_header_counts(path);
    check_off_face_indices(path);
  }
  if (format == Format::ply) check_ply_header(path);
}

/// What a parse failure means, for the message.
std::string parse_failure(Format format) {
  switch (format) {
    case Format::obj:
      return "cannot parse the file as OBJ (malformed or truncated)";
    case Format::off:
      // CGAL's OFF reader reports an out-of-range face index as a parse failure.
      return "cannot parse the file as OFF (malformed or truncated, or a face index out of "
             "range)";
    case Format::ply:
      return "cannot parse the file as PLY (malformed or truncated)";
  }
  return "cannot parse the file";
}

/// Points and polygons as read from a file, before any checks.
struct Soup {
  Positions vertices;
  Polygons polygons;
};

/// Copies CGAL-side points (anything with p[0..2]) into a (|V| × 3) array.
template <class Point>
Positions to_positions(const std::vector<Point>& points) {
  Positions vertices(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices(i, k) = points[i][k];
  return vertices;
}

/// Reads with CGAL. Returns false on a parse failure; `soup` then holds what was read so far.
bool read_soup(const std::string& path, Format format, Soup& soup) {
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
void check_index_range(const std::string& path, const Soup& soup) {
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
void check_triangles(const std::string& path, const Soup& soup) {
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
  Soup soup;
  bool ok = false;
  try {
    ok = read_soup(path, format, soup);
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
