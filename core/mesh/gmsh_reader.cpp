// Format: the Gmsh reference manual, section "MSH file format" (versions 2.2 and 4.1).
#include "mesh/gmsh_reader.hpp"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "mesh/text_lines.hpp"

namespace progsim {
namespace {

/// The Gmsh element type of a 4-node tetrahedron.
constexpr long long kTetType = 4;

/// The nodes read so far: positions in file order and a sorted tag → index table.
struct Nodes {
  Positions positions;
  std::vector<std::pair<long long, int>> tag_index;
  bool read = false;  ///< a $Nodes section has been read
};

/// Parses `token` as a whole number (a tag, type or flag); io_error naming `what` otherwise.
long long whole(const TextLines& lines, const TextLine& line, std::size_t k,
                const std::string& what) {
  long long value = 0;
  if (k >= line.tokens.size())
    lines.fail_parse(line.number, "expected " + what + " as word " + std::to_string(k + 1));
  if (!parse_whole(line.tokens[k], value))
    lines.fail_parse(line.number, what + " '" + line.tokens[k] + "' is not a whole number");
  return value;
}

/// Requires the next line to be exactly `marker` (such as "$EndNodes").
void expect_marker(TextLines& lines, const std::string& marker) {
  const TextLine line = lines.require(marker);
  if (line.tokens.size() != 1 || line.tokens[0] != marker)
    lines.fail_parse(line.number, "expected " + marker + ", found '" + line.tokens[0] + "'");
}

/// Reads "$MeshFormat / version file-type data-size / $EndMeshFormat"; returns 2 or 4.
int read_format(TextLines& lines) {
  TextLine line = lines.require("$MeshFormat");
  if (line.tokens[0] != "$MeshFormat")
    lines.fail_parse(line.number, "it does not start with $MeshFormat");
  line = lines.require("the format line");
  if (line.tokens.size() != 3)
    lines.fail_parse(line.number, "expected 'version file-type data-size'");
  if (line.tokens[1] != "0")
    lines.fail_io("binary MSH files are not supported (file-type " + line.tokens[1] +
                  " in $MeshFormat, line " + std::to_string(line.number) +
                  "); save the mesh as ASCII MSH 2.2 or 4.1");
  const std::string& version = line.tokens[0];
  if (version != "2.2" && version != "4.1")
    lines.fail_io("MSH version " + version + " is not supported (line " +
                  std::to_string(line.number) + "; progsim reads ASCII MSH 2.2 and 4.1)");
  expect_marker(lines, "$EndMeshFormat");
  return version == "2.2" ? 2 : 4;
}

/// Reads "x y z" from words first.. of `line` into node `index`.
void read_position(const TextLines& lines, const TextLine& line, std::size_t first, Nodes& nodes,
                   int index) {
  const std::string name = "node " + std::to_string(index + 1);
  if (line.tokens.size() < first + 3)
    lines.fail_parse(line.number, name + " has fewer than 3 coordinates");
  for (int k = 0; k < 3; ++k)
    nodes.positions(index, k) = lines.coordinate(line.number, line.tokens[first + k], name);
}

/// Sorts the tag table and rejects a tag given twice.
void index_tags(const TextLines& lines, Nodes& nodes) {
  std::sort(nodes.tag_index.begin(), nodes.tag_index.end());
  const auto same_tag = [](const auto& a, const auto& b) { return a.first == b.first; };
  const auto twice = std::adjacent_find(nodes.tag_index.begin(), nodes.tag_index.end(), same_tag);
  if (twice != nodes.tag_index.end())
    lines.fail_mesh("node tag " + std::to_string(twice->first) + " appears twice in $Nodes");
  nodes.read = true;
}

/// Allocates `count` nodes, declared on line `line` (each takes at least 8 bytes).
void start_nodes(TextLines& lines, const TextLine& line, std::size_t k, Nodes& nodes) {
  if (nodes.read) lines.fail_parse(line.number, "a second $Nodes section");
  if (k >= line.tokens.size()) lines.fail_parse(line.number, "expected the number of nodes");
  const std::size_t count = lines.count(line.number, line.tokens[k], 8, "nodes");
  nodes.positions.resize(static_cast<Eigen::Index>(count), 3);
  nodes.tag_index.reserve(count);
}

/// Version 2.2: "count", then count lines "tag x y z".
void read_nodes_v2(TextLines& lines, Nodes& nodes) {
  start_nodes(lines, lines.require("the number of nodes"), 0, nodes);
  for (int i = 0; i < nodes.positions.rows(); ++i) {
    const TextLine line = lines.require("node " + std::to_string(i + 1));
    nodes.tag_index.emplace_back(whole(lines, line, 0, "node tag"), i);
    read_position(lines, line, 1, nodes, i);
  }
}

/// Reads a version 4.1 block header "dim tag third count" and returns count, at most `left`.
std::size_t read_block_header(TextLines& lines, std::size_t left, const std::string& what,
                              long long& third) {
  const TextLine line = lines.require("an entity block of " + what);
  third = whole(lines, line, 2, "the block's third entry");
  const std::size_t count = lines.count(line.number, line.tokens.size() == 4 ? line.tokens[3] : "",
                                        1, what + " in the block");
  if (count > left)
    lines.fail_parse(line.number, "the block holds " + std::to_string(count) + " " + what +
                                      ", more than the " + std::to_string(left) +
                                      " the section header leaves");
  return count;
}

/// Rejects a version 4.1 section whose blocks hold fewer items than its header declares.
void check_total(const TextLines& lines, const TextLine& header, std::size_t read,
                 std::size_t total, const std::string& what) {
  if (read == total) return;
  lines.fail_parse(header.number, "the header declares " + std::to_string(total) + " " + what +
                                      " but its blocks hold " + std::to_string(read));
}

/// Reads the entity blocks of a version 4.1 section whose header is `header` ("blocks count
/// min max"): per block its header "dim tag third n", then read_block(third, n, before) with
/// `before` the items of the blocks before it. Checks that the blocks hold `total` items.
template <class ReadBlock>
void read_blocks(TextLines& lines, const TextLine& header, std::size_t total,
                 const std::string& what, ReadBlock&& read_block) {
  const long long blocks = whole(lines, header, 0, "the number of blocks of " + what);
  std::size_t read = 0;
  for (long long b = 0; b < blocks; ++b) {
    long long third = 0;
    const std::size_t n = read_block_header(lines, total - read, what, third);
    read_block(third, n, read);
    read += n;
  }
  check_total(lines, header, read, total, what);
}

/// Version 4.1: "blocks count min max", then per block "dim tag parametric n", n tag lines
/// and n coordinate lines.
void read_nodes_v4(TextLines& lines, Nodes& nodes) {
  const TextLine header = lines.require("the $Nodes header");
  start_nodes(lines, header, 1, nodes);
  const auto total = static_cast<std::size_t>(nodes.positions.rows());
  read_blocks(lines, header, total, "nodes", [&](long long, std::size_t n, std::size_t before) {
    for (std::size_t i = 0; i < n; ++i) {
      const TextLine line = lines.require("a node tag");
      nodes.tag_index.emplace_back(whole(lines, line, 0, "node tag"), static_cast<int>(before + i));
    }
    for (std::size_t i = 0; i < n; ++i)
      read_position(lines, lines.require("node coordinates"), 0, nodes,
                    static_cast<int>(before + i));
  });
}

/// The index of the node tagged by word k of `line`.
int node_index(const TextLines& lines, const TextLine& line, std::size_t k, const Nodes& nodes,
               std::size_t tet) {
  const long long tag = whole(lines, line, k, "node tag");
  const auto it =
      std::lower_bound(nodes.tag_index.begin(), nodes.tag_index.end(), std::make_pair(tag, -1));
  if (it != nodes.tag_index.end() && it->first == tag) return it->second;
  lines.fail_mesh("tet " + std::to_string(tet + 1) + " references node " + std::to_string(tag) +
                  ", which $Nodes does not define (line " + std::to_string(line.number) + ")");
}

/// Appends the tet whose four node tags are words first..first+3 of `line`.
void add_tet(const TextLines& lines, const TextLine& line, std::size_t first, const Nodes& nodes,
             std::vector<std::array<int, 4>>& tets) {
  if (line.tokens.size() != first + 4)
    lines.fail_parse(line.number, "a 4-node tetrahedron lists " +
                                      std::to_string(line.tokens.size() - first) + " nodes");
  std::array<int, 4> tet{};
  for (int k = 0; k < 4; ++k) tet[k] = node_index(lines, line, first + k, nodes, tets.size());
  tets.push_back(tet);
}

/// Version 2.2: "count", then count lines "tag type ntags tags... nodes...".
void read_elements_v2(TextLines& lines, const Nodes& nodes, std::vector<std::array<int, 4>>& tets) {
  const TextLine header = lines.require("the number of elements");
  const std::size_t count = lines.count(header.number, header.tokens[0], 8, "elements");
  for (std::size_t e = 0; e < count; ++e) {
    const TextLine line = lines.require("element " + std::to_string(e + 1));
    const long long type = whole(lines, line, 1, "element type");
    const long long tags = whole(lines, line, 2, "number of tags");
    if (tags < 0 || static_cast<std::size_t>(tags) > line.tokens.size() - 3)
      lines.fail_parse(line.number, "element declares " + std::to_string(tags) + " tags");
    if (type == kTetType) add_tet(lines, line, 3 + static_cast<std::size_t>(tags), nodes, tets);
  }
}

/// Version 4.1: "blocks count min max", then per block "dim tag type n" and n lines
/// "tag nodes...".
void read_elements_v4(TextLines& lines, const Nodes& nodes, std::vector<std::array<int, 4>>& tets) {
  const TextLine header = lines.require("the $Elements header");
  if (header.tokens.size() < 2) lines.fail_parse(header.number, "expected the number of elements");
  const std::size_t total = lines.count(header.number, header.tokens[1], 2, "elements");
  read_blocks(lines, header, total, "elements", [&](long long type, std::size_t n, std::size_t) {
    for (std::size_t i = 0; i < n; ++i) {
      const TextLine line = lines.require("an element");
      if (type == kTetType) add_tet(lines, line, 1, nodes, tets);
    }
  });
}

/// Reads the section opened by `line` up to its "$End..." line.
void read_section(TextLines& lines, const TextLine& line, int version, Nodes& nodes,
                  std::vector<std::array<int, 4>>& tets) {
  const std::string& name = line.tokens[0];
  if (name.size() < 2 || name[0] != '$')
    lines.fail_parse(line.number, "expected a section such as $Nodes, found '" + name + "'");
  const std::string end = "$End" + name.substr(1);
  if (name == "$Nodes") {
    version == 2 ? read_nodes_v2(lines, nodes) : read_nodes_v4(lines, nodes);
    index_tags(lines, nodes);
  } else if (name == "$Elements") {
    if (!nodes.read) lines.fail_parse(line.number, "$Elements before $Nodes");
    version == 2 ? read_elements_v2(lines, nodes, tets) : read_elements_v4(lines, nodes, tets);
  } else {  // a section progsim does not need
    for (TextLine skipped = lines.require(end); skipped.tokens[0] != end;)
      skipped = lines.require(end);
    return;
  }
  expect_marker(lines, end);
}

}  // namespace

TetMesh read_gmsh(const std::string& path) {
  TextLines lines(path, "Gmsh .msh", false);
  const int version = read_format(lines);
  Nodes nodes;
  std::vector<std::array<int, 4>> tets;
  for (TextLine line; lines.next(line);) read_section(lines, line, version, nodes, tets);
  TetMesh mesh{std::move(nodes.positions), Tets(static_cast<Eigen::Index>(tets.size()), 4)};
  for (std::size_t t = 0; t < tets.size(); ++t)
    mesh.tets.row(static_cast<Eigen::Index>(t)) =
        Eigen::Map<const Eigen::RowVector4i>(tets[t].data());
  return mesh;
}

}  // namespace progsim
