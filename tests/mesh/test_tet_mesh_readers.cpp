// Tet mesh readers: hand-written Medit, Gmsh 2.2 / 4.1 and TetGen files of tests/data/tet/
// read to the meshes they describe; malformed files are rejected with the right status and a
// message naming the file and the problem.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh/gmsh_reader.hpp"
#include "mesh/medit_reader.hpp"
#include "mesh/tet_mesh_io.hpp"
#include "mesh/tet_mesh_validation.hpp"
#include "mesh/tetgen_reader.hpp"
#include "mesh_test_support.hpp"
#include "tet_test_support.hpp"

using namespace progsim;
using progsim::test_support::expect_error;
using progsim::tet_test::cube5;
using progsim::tet_test::tet_data;
using progsim::tet_test::TetScratch;
using progsim::tet_test::unit_tet;

namespace {

/// Expects `mesh` to equal `expected` exactly (same vertex and tet order).
void expect_same_tet_mesh(const TetMesh& mesh, const TetMesh& expected) {
  ASSERT_EQ(mesh.num_vertices(), expected.num_vertices());
  ASSERT_EQ(mesh.num_tets(), expected.num_tets());
  EXPECT_EQ(mesh.vertices, expected.vertices);
  EXPECT_EQ(mesh.tets, expected.tets);
}

/// Expects read_tet_mesh(path) to throw `status` naming the path and `parts`.
void expect_tet_read_error(const std::string& path, Status status,
                           std::initializer_list<std::string> parts) {
  expect_error([&] { read_tet_mesh(path); }, status, {path + ": "});
  expect_error([&] { read_tet_mesh(path); }, status, parts);
}

}  // namespace

TEST(TetMeshReaders, MeditSingleTetSkipsSurfaceSections) {
  expect_same_tet_mesh(read_medit(tet_data("single_tet.mesh")), unit_tet());
}

TEST(TetMeshReaders, MeditCube) {
  const TetMesh mesh = read_tet_mesh(tet_data("cube5.mesh"));
  expect_same_tet_mesh(mesh, cube5());
  EXPECT_DOUBLE_EQ(tet_mesh_volume(mesh), 1.0);
  EXPECT_NO_THROW(validate_tet_mesh(mesh, "cube5.mesh"));
}

TEST(TetMeshReaders, Gmsh22KeepsOnlyTets) {
  // Tags 1..8 in order: the same indices as cube5; a point, a line and a triangle skipped.
  expect_same_tet_mesh(read_gmsh(tet_data("cube5_v22.msh")), cube5());
}

TEST(TetMeshReaders, Gmsh41MapsNonContiguousTagsInFileOrder) {
  const TetMesh mesh = read_tet_mesh(tet_data("cube5_v41.msh"));
  // Tag 10(k + 1) is cube5's vertex k; the file lists tags 50, 10, 30, 20, 40, 60, 70, 80.
  const int cube_vertex[8] = {4, 0, 2, 1, 3, 5, 6, 7};
  const TetMesh cube = cube5();
  ASSERT_EQ(mesh.num_vertices(), 8);
  for (int v = 0; v < 8; ++v)
    EXPECT_EQ(mesh.vertices.row(v), cube.vertices.row(cube_vertex[v])) << "vertex " << v;
  ASSERT_EQ(mesh.num_tets(), 5);
  for (int t = 0; t < 5; ++t)
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(cube_vertex[mesh.tets(t, k)], cube.tets(t, k)) << "tet " << t << " corner " << k;
  EXPECT_DOUBLE_EQ(tet_mesh_volume(mesh), 1.0);
  EXPECT_NO_THROW(validate_tet_mesh(mesh, "cube5_v41.msh"));
}

TEST(TetMeshReaders, TetGenPairNumberedFromOne) {
  expect_same_tet_mesh(read_tet_mesh(tet_data("cube5.node")), cube5());
  expect_same_tet_mesh(read_tet_mesh(tet_data("cube5.ele")), cube5());
}

TEST(TetMeshReaders, TetGenPairNumberedFromZero) {
  expect_same_tet_mesh(read_tetgen(tet_data("single_tet.node"), tet_data("single_tet.ele")),
                       unit_tet());
}

TEST(TetMeshReaders, NanCoordinateIsReadForValidation) {
  const TetMesh mesh = read_tet_mesh(tet_data("bad_nan.mesh"));
  EXPECT_TRUE(std::isnan(mesh.vertices(2, 1)));
}

TEST(TetMeshReaders, UnknownExtensionAndMissingFile) {
  expect_tet_read_error(tet_data("cube5.obj"), Status::io_error,
                        {"unknown tet mesh format '.obj'"});
  expect_tet_read_error(tet_data("no_such_file.mesh"), Status::io_error, {"cannot read the file"});
}

TEST(TetMeshReaders, TruncatedFile) {
  expect_tet_read_error(tet_data("bad_truncated.mesh"), Status::io_error, {"line 7", "truncated"});
}

TEST(TetMeshReaders, CountLargerThanTheFile) {
  expect_tet_read_error(tet_data("bad_huge_count.mesh"), Status::io_error,
                        {"line 4", "99999999999999 Vertices", "more than the file's"});
}

TEST(TetMeshReaders, IndexOutOfRange) {
  expect_tet_read_error(tet_data("bad_index.mesh"), Status::invalid_mesh,
                        {"tet 1 references vertex '9'", "[1, 5)", "line 11"});
  expect_tet_read_error(tet_data("bad_index.ele"), Status::invalid_mesh,
                        {"bad_index.ele: ", "tet 1 references vertex '0'", "[1, 5)", "line 2"});
  expect_tet_read_error(tet_data("bad_missing_node.msh"), Status::invalid_mesh,
                        {"tet 1 references node 7", "$Nodes does not define", "line 19"});
}

TEST(TetMeshReaders, BinaryGmshIsRefused) {
  expect_tet_read_error(tet_data("bad_binary.msh"), Status::io_error,
                        {"binary MSH files are not supported", "file-type 1"});
}

TEST(TetMeshReaders, TetGenPointsOutOfSequence) {
  expect_tet_read_error(tet_data("bad_sequence.node"), Status::io_error,
                        {"point index 4 is out of sequence", "3 expected", "line 4"});
}

class TetMeshReaderErrors : public TetScratch {};

TEST_F(TetMeshReaderErrors, MeditHeaderDimensionAndKeywords) {
  expect_tet_read_error(write("a.mesh", "Vertices 0\n"), Status::io_error,
                        {"Medit .mesh", "line 1", "MeshVersionFormatted"});
  expect_tet_read_error(write("b.mesh", "MeshVersionFormatted 2 Dimension 2\n"), Status::io_error,
                        {"Dimension 2", "3D"});
  expect_tet_read_error(write("c.mesh", "MeshVersionFormatted 2\nDimension 3\nFoo 3\n"),
                        Status::io_error, {"line 3", "unknown keyword 'Foo'"});
  expect_tet_read_error(write("d.mesh", "MeshVersionFormatted 2\nVertices 0\nVertices 0\n"),
                        Status::io_error, {"line 3", "a second Vertices section"});
  expect_tet_read_error(write("e.mesh", "MeshVersionFormatted 2\nVertices -1\n"), Status::io_error,
                        {"line 2", "'-1' is not a whole number"});
  expect_tet_read_error(write("f.mesh", "MeshVersionFormatted 2\nVertices 1\n0 x 0 0\n"),
                        Status::io_error, {"line 3", "vertex 1 coordinate 'x' is not a number"});
  expect_tet_read_error(write("g.mesh", "MeshVersionFormatted 2\nTetrahedra 0\n"),
                        Status::invalid_mesh, {"Tetrahedra come before Vertices"});
  expect_tet_read_error(write("h.mesh", "MeshVersionFormatted 2\nTriangles 2\n1 2 3 0\n"),
                        Status::io_error, {"truncated"});
}

TEST_F(TetMeshReaderErrors, GmshStructure) {
  const std::string format = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  expect_tet_read_error(write("a.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n"), Status::io_error,
                        {"MSH version 3.0 is not supported"});
  expect_tet_read_error(write("b.msh", "$Nodes\n"), Status::io_error,
                        {"Gmsh .msh", "line 1", "$MeshFormat"});
  expect_tet_read_error(write("c.msh", format + "$Elements\n0 0 0 0\n$EndElements\n"),
                        Status::io_error, {"line 4", "$Elements before $Nodes"});
  expect_tet_read_error(write("d.msh", format + "$Nodes\n1 3 1 3\n0 1 0 2\n1\n2\n0 0 0\n0 0 1\n"
                                                "$EndNodes\n"),
                        Status::io_error, {"line 5", "declares 3 nodes but its blocks hold 2"});
  expect_tet_read_error(write("e.msh", format + "$Nodes\n1 2 1 2\n0 1 0 2\n1\n1\n0 0 0\n0 0 1\n"
                                                "$EndNodes\n"),
                        Status::invalid_mesh, {"node tag 1 appears twice"});
  expect_tet_read_error(write("f.msh", format + "$Nodes\n1 99999999 1 2\n"), Status::io_error,
                        {"line 5", "99999999 nodes", "more than the file's"});
  expect_tet_read_error(write("g.msh", format + "$Comments\nhello\n"), Status::io_error,
                        {"$EndComments", "truncated"});
  expect_tet_read_error(write("h.msh", format + "$Nodes\n0 0 0 0\n$Foo\n"), Status::io_error,
                        {"line 6", "expected $EndNodes, found '$Foo'"});
}

TEST_F(TetMeshReaderErrors, TetGenHeaders) {
  write("a.ele", "1 4 0\n1 1 2 3 4\n");
  expect_tet_read_error(write("a.node", "4 2 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"),
                        Status::io_error, {"TetGen .node", "line 1", "the dimension 3"});
  write("b.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  expect_tet_read_error(write("b.ele", "1 6 0\n1 1 2 3 4 1 1\n"), Status::io_error,
                        {"TetGen .ele", "4 or 10 nodes"});
  write("c.node", "1 3 1 1\n1 0 0 0 5\n");
  expect_tet_read_error(path("c.node"), Status::io_error,
                        {"point 0 has 5 words, fewer than the 6"});
  write("d.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  expect_tet_read_error(write("d.ele", "1 4 0\n1 1 2 3\n"), Status::io_error,
                        {"tet 1 has 4 words, fewer than the 5"});
}
