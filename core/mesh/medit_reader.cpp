// Format: INRIA's "MEDIT" file description (Frey), as written by libMeshb (ISC Gamma).
#include "mesh/medit_reader.hpp"

#include <map>

#include "mesh/text_lines.hpp"

namespace progsim {
namespace {

/// The words of a Medit file one by one, across lines.
class Words {
 public:
  explicit Words(TextLines& lines) : lines_(lines) {}

  /// The next word; false at the end of the file.
  bool next(std::string& word) {
    while (at_ == line_.tokens.size()) {
      if (!lines_.next(line_)) return false;
      at_ = 0;
    }
    word = line_.tokens[at_++];
    return true;
  }

  /// The next word; a missing one is a truncated file, `expected` names what was due.
  std::string require(const std::string& expected) {
    std::string word;
    if (!next(word))
      lines_.fail_parse(lines_.line_number(), "the file ends before " + expected + " (truncated)");
    return word;
  }

  /// The line of the last word read.
  std::size_t line() const { return line_.number; }

  TextLines& lines() { return lines_; }

 private:
  TextLines& lines_;
  TextLine line_;
  std::size_t at_ = 0;
};

/// Words per item of the sections that are skipped.
const std::map<std::string, int>& skipped_sections() {
  static const std::map<std::string, int> sections{{"Edges", 3},
                                                   {"Triangles", 4},
                                                   {"Quadrilaterals", 5},
                                                   {"Hexahedra", 9},
                                                   {"Prisms", 7},
                                                   {"Corners", 1},
                                                   {"Ridges", 1},
                                                   {"RequiredVertices", 1},
                                                   {"RequiredEdges", 1},
                                                   {"RequiredTriangles", 1},
                                                   {"RequiredQuadrilaterals", 1},
                                                   {"Normals", 3},
                                                   {"NormalAtVertices", 2},
                                                   {"NormalAtTriangleVertices", 3},
                                                   {"Tangents", 3},
                                                   {"TangentAtVertices", 2},
                                                   {"TangentAtEdges", 3}};
  return sections;
}

/// Reads a section's item count: `words_per_item` words of at least 2 bytes each per item.
std::size_t read_count(Words& words, const std::string& section, int words_per_item) {
  const std::string word = words.require("the number of " + section);
  return words.lines().count(words.line(), word, 2 * words_per_item, section);
}

/// Reads the integer after `keyword`.
long long read_integer(Words& words, const std::string& keyword) {
  const std::string word = words.require("the value of " + keyword);
  long long value = 0;
  if (!parse_whole(word, value))
    words.lines().fail_parse(words.line(), keyword + " '" + word + "' is not a whole number");
  return value;
}

void read_header(Words& words) {
  std::string word;
  if (!words.next(word) || word != "MeshVersionFormatted")
    words.lines().fail_parse(words.line(), "it does not start with MeshVersionFormatted");
  read_integer(words, "MeshVersionFormatted");
}

Positions read_vertices(Words& words) {
  const std::size_t count = read_count(words, "Vertices", 4);
  Positions vertices(static_cast<Eigen::Index>(count), 3);
  for (std::size_t v = 0; v < count; ++v) {
    const std::string name = "vertex " + std::to_string(v + 1);
    for (int k = 0; k < 3; ++k) {
      const std::string word = words.require(name);
      vertices(static_cast<Eigen::Index>(v), k) =
          words.lines().coordinate(words.line(), word, name);
    }
    read_integer(words, name + " reference");
  }
  return vertices;
}

Tets read_tets(Words& words, std::size_t num_vertices) {
  const std::size_t count = read_count(words, "Tetrahedra", 5);
  Tets tets(static_cast<Eigen::Index>(count), 4);
  for (std::size_t t = 0; t < count; ++t) {
    const std::string name = "tet " + std::to_string(t + 1);
    for (int k = 0; k < 4; ++k) {
      const std::string word = words.require(name);
      tets(static_cast<Eigen::Index>(t), k) =
          words.lines().index(words.line(), word, 1, num_vertices, name);
    }
    read_integer(words, name + " reference");
  }
  return tets;
}

void skip_section(Words& words, const std::string& section, int words_per_item) {
  const std::size_t count = read_count(words, section, words_per_item);
  for (std::size_t i = 0; i < count * words_per_item; ++i) words.require(section + " items");
}

/// Reads one section opened by `keyword`; `seen` collects the keywords so far.
void read_section(Words& words, const std::string& keyword, TetMesh& mesh,
                  std::map<std::string, int>& seen) {
  if (seen[keyword]++ > 0)
    words.lines().fail_parse(words.line(), "a second " + keyword + " section");
  const auto skipped = skipped_sections().find(keyword);
  if (keyword == "Dimension") {
    const long long dimension = read_integer(words, keyword);
    if (dimension != 3)
      words.lines().fail_io("Dimension " + std::to_string(dimension) +
                            ": progsim reads 3D tet meshes only (line " +
                            std::to_string(words.line()) + ")");
  } else if (keyword == "Vertices") {
    mesh.vertices = read_vertices(words);
  } else if (keyword == "Tetrahedra") {
    if (seen.count("Vertices") == 0)
      words.lines().fail_mesh("Tetrahedra come before Vertices (line " +
                              std::to_string(words.line()) + ")");
    mesh.tets = read_tets(words, static_cast<std::size_t>(mesh.vertices.rows()));
  } else if (skipped != skipped_sections().end()) {
    skip_section(words, keyword, skipped->second);
  } else {
    words.lines().fail_parse(words.line(), "unknown keyword '" + keyword + "'");
  }
}

}  // namespace

TetMesh read_medit(const std::string& path) {
  TextLines lines(path, "Medit .mesh");
  Words words(lines);
  read_header(words);
  TetMesh mesh;
  std::map<std::string, int> seen;
  for (std::string keyword; words.next(keyword) && keyword != "End";)
    read_section(words, keyword, mesh, seen);
  return mesh;
}

}  // namespace progsim
