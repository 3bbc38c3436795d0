#include "mesh/off_reader.hpp"

#include <string_view>

#include "mesh/text_lines.hpp"

namespace progsim {
namespace {

/// Checks the keyword `[ST][C][N]OFF` that opens the file. Binary, 4D and nD OFF are refused.
void check_keyword(const TextLines& lines, const TextLine& first) {
  std::string_view keyword = first.tokens[0];
  for (const std::string_view prefix : {"ST", "C", "N"})
    if (keyword.substr(0, prefix.size()) == prefix) keyword.remove_prefix(prefix.size());
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF")
    lines.fail_parse(first.number, "it does not start with the keyword OFF");
  if (keyword != "OFF")
    lines.fail_parse(first.number,
                     "keyword '" + first.tokens[0] + "': 4D and nD OFF are not supported");
  if (first.tokens.size() > 1 && first.tokens[1].rfind("BINARY", 0) == 0)
    lines.fail_io("binary OFF is not supported; save the mesh as text OFF, OBJ or PLY");
}

/// Vertex and face counts of the header.
struct OffCounts {
  std::size_t vertices = 0;
  std::size_t faces = 0;
};

/// Reads "|V| |F| [|E|]" from the keyword line's remaining words or else the next line, and
/// rejects counts the file is too short to hold before anything is allocated: a vertex line
/// takes at least 6 bytes ("0 0 0\n") and a face line at least 2 ("0\n").
OffCounts read_counts(TextLines& lines, const TextLine& first) {
  const std::uintmax_t file_size = lines.file_size();
  TextLine line{first.number, {first.tokens.begin() + 1, first.tokens.end()}};
  if (line.tokens.empty()) line = lines.require("the vertex and face counts");
  OffCounts counts;
  if (line.tokens.size() < 2 || line.tokens.size() > 3 ||
      !parse_whole(line.tokens[0], counts.vertices) || !parse_whole(line.tokens[1], counts.faces))
    lines.fail_parse(line.number, "expected the counts '|V| |F| [|E|]' as whole numbers");
  if (counts.vertices <= file_size / 6 && counts.faces <= file_size / 2 &&
      6 * counts.vertices + 2 * counts.faces <= file_size)
    return counts;
  lines.fail_io("the header declares " + std::to_string(counts.vertices) + " vertices and " +
                std::to_string(counts.faces) + " faces, more than the file's " +
                std::to_string(file_size) + " bytes can hold (truncated file or corrupt header)");
}

/// Reads the first three numbers of each of `count` vertex lines.
Positions read_vertices(TextLines& lines, std::size_t count) {
  Positions vertices(static_cast<Eigen::Index>(count), 3);
  for (std::size_t v = 0; v < count; ++v) {
    const TextLine line = lines.require("vertex " + std::to_string(v));
    if (line.tokens.size() < 3)
      lines.fail_parse(line.number,
                       "vertex " + std::to_string(v) + " has fewer than 3 coordinates");
    for (int k = 0; k < 3; ++k) {
      double& x = vertices(static_cast<Eigen::Index>(v), k);
      if (!parse_whole(line.tokens[k], x))
        lines.fail_parse(line.number, "vertex " + std::to_string(v) + " coordinate '" +
                                          line.tokens[k] + "' is not a number");
    }
  }
  return vertices;
}

/// Reads face `f` from `line`: its size k, then k vertex indices in [0, num_vertices).
std::vector<std::size_t> read_face(const TextLines& lines, const TextLine& line, std::size_t f,
                                   std::size_t num_vertices) {
  const std::string name = "face " + std::to_string(f);
  std::size_t k = 0;
  if (!parse_whole(line.tokens[0], k))
    lines.fail_mesh(name + " has '" + line.tokens[0] + "' vertices, not a whole number");
  if (k > line.tokens.size() - 1)
    lines.fail_parse(line.number, name + " declares " + std::to_string(k) + " vertices but lists " +
                                      std::to_string(line.tokens.size() - 1));
  std::vector<std::size_t> polygon(k);
  for (std::size_t i = 0; i < k; ++i) {
    const std::string& token = line.tokens[i + 1];
    if (!parse_whole(token, polygon[i]) || polygon[i] >= num_vertices)
      lines.fail_mesh(name + " references vertex '" + token + "', not an index in [0, " +
                      std::to_string(num_vertices) + ")");
  }
  return polygon;
}

}  // namespace

PolygonSoup read_off(const std::string& path) {
  TextLines lines(path, "OFF");
  const TextLine first = lines.require("the keyword OFF");
  check_keyword(lines, first);
  const OffCounts counts = read_counts(lines, first);
  PolygonSoup soup{read_vertices(lines, counts.vertices), {}};
  soup.polygons.reserve(counts.faces);
  for (std::size_t f = 0; f < counts.faces; ++f)
    soup.polygons.push_back(
        read_face(lines, lines.require("face " + std::to_string(f)), f, counts.vertices));
  return soup;
}

}  // namespace progsim
