#include "mesh/tet_mesh_io.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <ostream>

#include "common/error.hpp"
#include "common/file_output.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/medit_reader.hpp"
#include "mesh/tetgen_reader.hpp"

namespace progsim {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// `path` with its extension replaced by `ext` in the same letter case as the old one.
std::string sibling(const std::filesystem::path& path, std::string ext) {
  const std::string old = path.extension().string();
  if (std::all_of(old.begin() + 1, old.end(), [](unsigned char c) { return std::isupper(c); }))
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return std::filesystem::path(path).replace_extension(ext).string();
}

/// Writes the vertex rows, each "x y z" followed by `suffix`, with 17 significant digits.
void put_vertices(std::ostream& out, const Positions& vertices, const char* suffix) {
  out.precision(17);
  for (Eigen::Index v = 0; v < vertices.rows(); ++v)
    out << vertices(v, 0) << ' ' << vertices(v, 1) << ' ' << vertices(v, 2) << suffix << '\n';
}

/// Writes the tet rows, each `prefix` then "i j k l" shifted by `base`, then `suffix`.
void put_tets(std::ostream& out, const Tets& tets, const char* prefix, int base,
              const char* suffix) {
  for (Eigen::Index t = 0; t < tets.rows(); ++t)
    out << prefix << tets(t, 0) + base << ' ' << tets(t, 1) + base << ' ' << tets(t, 2) + base
        << ' ' << tets(t, 3) + base << suffix << '\n';
}

}  // namespace

bool is_tet_mesh_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".mesh" || ext == ".msh" || ext == ".node" || ext == ".ele";
}

TetMesh read_tet_mesh(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".mesh") return read_medit(path);
  if (ext == ".msh") return read_gmsh(path);
  if (ext == ".node") return read_tetgen(path, sibling(path, ".ele"));
  if (ext == ".ele") return read_tetgen(sibling(path, ".node"), path);
  fail(Status::io_error,
       path + ": unknown tet mesh format '" + ext + "' (known: .mesh, .msh, .node/.ele)");
}

void write_tet_mesh_medit(const std::string& path, const TetMesh& mesh) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n" << mesh.num_vertices() << '\n';
    put_vertices(out, mesh.vertices, " 0");
    out << "\nTetrahedra\n" << mesh.num_tets() << '\n';
    put_tets(out, mesh.tets, "", 1, " 0");
    out << "\nEnd\n";
  });
}

void write_tet_mesh_vtk(const std::string& path, const TetMesh& mesh) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# vtk DataFile Version 3.0\nprogsim tet mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n"
        << "POINTS " << mesh.num_vertices() << " double\n";
    put_vertices(out, mesh.vertices, "");
    out << "CELLS " << mesh.num_tets() << ' ' << 5 * mesh.num_tets() << '\n';
    put_tets(out, mesh.tets, "4 ", 0, "");
    out << "CELL_TYPES " << mesh.num_tets() << '\n';
    for (int t = 0; t < mesh.num_tets(); ++t) out << "10\n";
  });
}

}  // namespace progsim
