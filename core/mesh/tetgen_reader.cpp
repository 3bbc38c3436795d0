// Format: the TetGen manual (Si), §5.2 "Files formats": .node and .ele files.
#include "mesh/tetgen_reader.hpp"

#include "mesh/text_lines.hpp"

namespace progsim {
namespace {

/// `line`'s word k as a whole number in [low, high]; io_error naming `what` otherwise.
long long header_value(const TextLines& lines, const TextLine& line, std::size_t k,
                       const std::string& what, long long low, long long high) {
  long long value = 0;
  if (k < line.tokens.size() && parse_whole(line.tokens[k], value) && value >= low && value <= high)
    return value;
  lines.fail_parse(line.number, "expected " + what + " (a whole number in [" + std::to_string(low) +
                                    ", " + std::to_string(high) + "]) as word " +
                                    std::to_string(k + 1) + " of the header");
}

/// Requires at least `words` words on `line`, item `name`.
void require_words(const TextLines& lines, const TextLine& line, std::size_t words,
                   const std::string& name) {
  if (line.tokens.size() < words)
    lines.fail_parse(line.number, name + " has " + std::to_string(line.tokens.size()) +
                                      " words, fewer than the " + std::to_string(words) +
                                      " the header implies");
}

/// The points of a .node file and the index of its first point.
struct NodeFile {
  Positions vertices;
  long long first = 0;
};

/// Checks that point `i` (from 0) carries index first + i; the first point sets `first`.
void check_sequence(const TextLines& lines, const TextLine& line, std::size_t i, long long& first) {
  long long index = 0;
  if (!parse_whole(line.tokens[0], index))
    lines.fail_parse(line.number, "point index '" + line.tokens[0] + "' is not a whole number");
  if (i == 0 && (index == 0 || index == 1)) first = index;
  if (index != first + static_cast<long long>(i))
    lines.fail_parse(line.number, "point index " + line.tokens[0] + " is out of sequence (" +
                                      (i == 0 ? std::string("0 or 1") : std::to_string(first + i)) +
                                      " expected)");
}

NodeFile read_nodes(const std::string& path) {
  TextLines lines(path, "TetGen .node");
  const TextLine header = lines.require("the header");
  const std::size_t count = lines.count(header.number, header.tokens[0], 8, "points");
  header_value(lines, header, 1, "the dimension 3", 3, 3);
  const long long attributes = header_value(lines, header, 2, "the number of attributes", 0,
                                            static_cast<long long>(lines.file_size()));
  const long long markers = header_value(lines, header, 3, "the number of markers", 0, 1);
  NodeFile nodes{Positions(static_cast<Eigen::Index>(count), 3), 0};
  for (std::size_t i = 0; i < count; ++i) {
    const std::string name = "point " + std::to_string(i);
    const TextLine line = lines.require(name);
    require_words(lines, line, 4 + attributes + markers, name);
    check_sequence(lines, line, i, nodes.first);
    for (int k = 0; k < 3; ++k)
      nodes.vertices(static_cast<Eigen::Index>(i), k) =
          lines.coordinate(line.number, line.tokens[1 + k], name);
  }
  return nodes;
}

Tets read_elements(const std::string& path, const NodeFile& nodes) {
  TextLines lines(path, "TetGen .ele");
  const TextLine header = lines.require("the header");
  const long long per_tet = header_value(lines, header, 1, "the nodes per tet", 4, 10);
  if (per_tet != 4 && per_tet != 10)
    lines.fail_parse(header.number, "tets have 4 or 10 nodes, not " + header.tokens[1]);
  const std::size_t count = lines.count(header.number, header.tokens[0], 2 * (1 + per_tet), "tets");
  const long long attributes = header_value(lines, header, 2, "the number of attributes", 0,
                                            static_cast<long long>(lines.file_size()));
  Tets tets(static_cast<Eigen::Index>(count), 4);
  const std::size_t num_vertices = static_cast<std::size_t>(nodes.vertices.rows());
  for (std::size_t t = 0; t < count; ++t) {
    const std::string name = "tet " + std::to_string(nodes.first + t);
    const TextLine line = lines.require(name);
    require_words(lines, line, 1 + per_tet + attributes, name);
    for (int k = 0; k < 4; ++k)
      tets(static_cast<Eigen::Index>(t), k) =
          lines.index(line.number, line.tokens[1 + k], nodes.first, num_vertices, name);
  }
  return tets;
}

}  // namespace

TetMesh read_tetgen(const std::string& node_path, const std::string& ele_path) {
  NodeFile nodes = read_nodes(node_path);
  Tets tets = read_elements(ele_path, nodes);
  return TetMesh{std::move(nodes.vertices), std::move(tets)};
}

}  // namespace progsim
