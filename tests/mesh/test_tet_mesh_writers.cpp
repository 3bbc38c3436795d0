// Tet mesh writers: Medit and legacy VTK files read back to the same doubles and indices,
// nothing half-written is left behind, and the boundary goes out through write_mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mesh/mesh_io.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_generators.hpp"
#include "mesh/tet_mesh_io.hpp"
#include "mesh_test_support.hpp"
#include "tet_test_support.hpp"

using namespace progsim;
using progsim::test_support::expect_error;
using progsim::tet_test::TetScratch;

namespace {

/// A box whose coordinates need all 17 significant digits.
TetMesh irregular_tet_box() {
  TetMesh mesh = make_tet_box(Vec3(0.3, 0.7, 1.1), 2, 2, 3);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    mesh.vertices.row(v) *= 1.0 + 1e-3 * std::sin(13.0 * v + 0.2);
  return mesh;
}

/// Reads a legacy VTK unstructured grid as written by write_tet_mesh_vtk, checking its keywords.
TetMesh parse_tet_vtk(const std::string& path) {
  std::ifstream in(path);
  std::string line, word;
  std::getline(in, line);
  EXPECT_EQ(line, "# vtk DataFile Version 3.0");
  std::getline(in, line);  // title
  std::getline(in, line);
  EXPECT_EQ(line, "ASCII");
  std::getline(in, line);
  EXPECT_EQ(line, "DATASET UNSTRUCTURED_GRID");
  int n = 0, m = 0, size = 0;
  in >> word >> n >> line;
  EXPECT_EQ(word + " " + line, "POINTS double");
  TetMesh mesh;
  mesh.vertices.resize(n, 3);
  for (int v = 0; v < n; ++v)
    in >> mesh.vertices(v, 0) >> mesh.vertices(v, 1) >> mesh.vertices(v, 2);
  in >> word >> m >> size;
  EXPECT_EQ(word, "CELLS");
  EXPECT_EQ(size, 5 * m);
  mesh.tets.resize(m, 4);
  for (int t = 0; t < m; ++t) {
    int corners = 0;
    in >> corners >> mesh.tets(t, 0) >> mesh.tets(t, 1) >> mesh.tets(t, 2) >> mesh.tets(t, 3);
    EXPECT_EQ(corners, 4) << "cell " << t;
  }
  int types = 0;
  in >> word >> types;
  EXPECT_EQ(word, "CELL_TYPES");
  EXPECT_EQ(types, m);
  for (int t = 0; t < m; ++t) {
    int type = 0;
    in >> type;
    EXPECT_EQ(type, 10) << "cell " << t;
  }
  EXPECT_TRUE(static_cast<bool>(in));
  in >> word;
  EXPECT_TRUE(in.eof()) << "trailing '" << word << "'";
  return mesh;
}

}  // namespace

class TetMeshWriters : public TetScratch {
 protected:
  /// Writes a box with `write`, reads it back with `read`: the same doubles and indices, and
  /// no partial file left.
  template <class Write, class Read>
  void expect_exact_round_trip(Write write, Read read, const std::string& name) const {
    const TetMesh mesh = irregular_tet_box();
    write(path(name), mesh);
    const TetMesh back = read(path(name));
    EXPECT_EQ(back.vertices, mesh.vertices);
    EXPECT_EQ(back.tets, mesh.tets);
    EXPECT_FALSE(std::filesystem::exists(path(name + ".partial")));
  }
};

TEST_F(TetMeshWriters, MeditRoundTripIsExact) {
  expect_exact_round_trip(write_tet_mesh_medit, read_tet_mesh, "box.mesh");
}

TEST_F(TetMeshWriters, VtkRoundTripIsExact) {
  expect_exact_round_trip(write_tet_mesh_vtk, parse_tet_vtk, "box.vtk");
}

TEST_F(TetMeshWriters, VtkOfTheUnitTetLineByLine) {
  write_tet_mesh_vtk(path("tet.vtk"), tet_test::unit_tet());
  std::ifstream in(path("tet.vtk"));
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(),
            "# vtk DataFile Version 3.0\nprogsim tet mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n"
            "POINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
            "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n");
}

TEST_F(TetMeshWriters, UnwritablePathLeavesNothing) {
  const std::string target = path("missing_dir/box.mesh");
  expect_error([&] { write_tet_mesh_medit(target, tet_test::unit_tet()); }, Status::io_error,
               {target, "cannot open the file for writing"});
  expect_error([&] { write_tet_mesh_vtk(path("missing_dir/box.vtk"), tet_test::unit_tet()); },
               Status::io_error, {"box.vtk: cannot open"});
  EXPECT_FALSE(std::filesystem::exists(path("missing_dir")));
}

TEST_F(TetMeshWriters, BoundaryAsObjAndPly) {
  const TetBoundary boundary = extract_tet_boundary(make_tet_box(Vec3(1, 1, 1), 2, 1, 1));
  for (const char* name : {"boundary.obj", "boundary.ply"}) {
    write_mesh(path(name), boundary.surface);
    const TriangleMesh back = read_mesh(path(name));
    EXPECT_EQ(back.vertices, boundary.surface.vertices) << name;
    EXPECT_EQ(back.faces, boundary.surface.faces) << name;
    EXPECT_NO_THROW(validate_mesh(back, name));
  }
}
