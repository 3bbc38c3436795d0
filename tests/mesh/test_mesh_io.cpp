// Mesh IO: exact round trips in OBJ, OFF and PLY, hand-written files, and malformed files
// (tests/data/) rejected with the right status and a message naming the file and the face.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh_test_support.hpp"

using namespace progsim;
using progsim::test_support::expect_error;
namespace fs = std::filesystem;

namespace {

std::string data_file(const std::string& name) {
  return (fs::path(PROGSIM_TEST_DATA_DIR) / name).string();
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A sphere whose coordinates need all 17 significant digits (no short decimal forms).
TriangleMesh irregular_sphere() {
  TriangleMesh mesh = make_sphere(0.37, 2);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    mesh.vertices.row(v) *= 1.0 + 1e-3 * std::sin(17.0 * v + 0.1);
  return mesh;
}

}  // namespace

class MeshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("progsim_mesh_io_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Writes `text` to a file in the temporary directory and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }

  fs::path dir_;
};

namespace {

void expect_read_error(const std::string& name, Status status,
                       std::initializer_list<std::string> parts) {
  SCOPED_TRACE(name);
  expect_error([&] { read_mesh(data_file(name)); }, status, parts);
}

}  // namespace

TEST_F(MeshIo, RoundTripsEveryFormatExactly) {
  const TriangleMesh mesh = irregular_sphere();
  for (const std::string name : {"a.obj", "a.off", "a.ply", "upper.OBJ"}) {
    SCOPED_TRACE(name);
    const std::string path = (dir_ / name).string();
    write_mesh(path, mesh);
    const TriangleMesh back = read_mesh(path);
    ASSERT_EQ(back.num_vertices(), mesh.num_vertices());
    ASSERT_EQ(back.num_faces(), mesh.num_faces());
    EXPECT_EQ((back.vertices - mesh.vertices).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(back.faces, mesh.faces);
  }
  // Each file is in the format its extension names.
  EXPECT_EQ(file_text(dir_ / "a.off").rfind("OFF", 0), 0u);
  EXPECT_EQ(file_text(dir_ / "a.ply").rfind("ply", 0), 0u);
  EXPECT_NE(file_text(dir_ / "a.obj").find("\nf "), std::string::npos);
}

TEST_F(MeshIo, ReadsHandWrittenFiles) {
  // OBJ with comments, normals, texture coordinates, v/vt/vn faces and relative indices.
  const std::string obj = write("square.obj",
                                "# unit square\n"
                                "o square\n"
                                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\n"
                                "vt 0 0\nvn 0 0 1\n"
                                "f 1/1/1 2/1/1 3/1/1\n"
                                "f -4 -2 -1\n");
  const std::string off = write("square.off",
                                "OFF\n# unit square\n4 2 0\n"
                                "0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n"
                                "3 0 1 2\n3 0 2 3\n");
  const std::string ply = write("square.ply",
                                "ply\nformat ascii 1.0\nelement vertex 4\n"
                                "property float x\nproperty float y\nproperty float z\n"
                                "element face 2\nproperty list uchar int vertex_indices\n"
                                "end_header\n"
                                "0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n3 0 1 2\n3 0 2 3\n");
  Positions vertices(4, 3);
  vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0.5;
  Faces faces(2, 3);
  faces << 0, 1, 2, 0, 2, 3;
  for (const std::string& path : {obj, off, ply}) {
    SCOPED_TRACE(path);
    const TriangleMesh mesh = read_mesh(path);
    EXPECT_EQ(mesh.vertices, vertices);
    EXPECT_EQ(mesh.faces, faces);
    EXPECT_NO_THROW(validate_mesh(mesh, path));
  }
}

TEST_F(MeshIo, RejectsBadIndicesAndPolygonsAsInvalidMeshes) {
  // Vertex 5 of 4 (1-based): CGAL's OBJ reader lets it through, read_mesh catches it.
  expect_read_error("bad_index.obj", Status::invalid_mesh,
                    {"bad_index.obj: face 1 references vertex 4 (counting from 0), but the file "
                     "has 4 vertices"});
  // Vertex 9 of 4: CGAL's OBJ reader fails on it; the message still names the face.
  expect_read_error("bad_index_far.obj", Status::invalid_mesh,
                    {"bad_index_far.obj: face 1 references vertex 8"});
  // read_off checks each index is a whole number in range (CGAL's OFF scanner cast them
  // to size_t, undefined for negative or huge values).
  expect_read_error("bad_index.off", Status::invalid_mesh,
                    {"bad_index.off: face 1 references vertex '7'", "[0, 4)"});
  expect_read_error("huge_index.off", Status::invalid_mesh,
                    {"huge_index.off: face 0 references vertex '37777777777777777777777777'"});
  expect_read_error("negative_face_size.off", Status::invalid_mesh,
                    {"negative_face_size.off: face 0 has '-1' vertices"});
  expect_read_error("negative_index.ply", Status::invalid_mesh,
                    {"negative_index.ply: face 1 references vertex -1"});
  expect_read_error("quad_face.obj", Status::invalid_mesh,
                    {"quad_face.obj: face 2 has 4 vertices"});
}

TEST_F(MeshIo, RejectsUnparsableFilesAsIoErrors) {
  expect_read_error("garbage.off", Status::io_error, {"garbage.off: cannot parse"});
  expect_read_error("truncated.ply", Status::io_error, {"truncated.ply: cannot parse"});
  // Found by the fuzz target: CGAL dereferences null for integer vertex coordinates.
  expect_read_error("integer_coordinate.ply", Status::io_error,
                    {"integer_coordinate.ply: cannot parse", "'y' has type 'uint32'"});
  // Found by the fuzz target: "element verertex -1." made CGAL loop over 2^64 − 1 items.
  expect_read_error("negative_element_count.ply", Status::io_error,
                    {"negative_element_count.ply: cannot parse", "element 'verertex'", "'-1.'"});
  // Found by the fuzz target: a face list counted in int claiming 2^31 − 1 indices made CGAL
  // allocate 8 GB before reading them.
  expect_read_error("huge_list_count.ply", Status::io_error,
                    {"huge_list_count.ply: cannot parse", "counts its items with type 'int'"});
}

TEST_F(MeshIo, LeavesGeometryAndManifoldnessToValidation) {
  const TriangleMesh nan_mesh = read_mesh(data_file("nan_vertex.obj"));
  EXPECT_EQ(nan_mesh.num_vertices(), 4);
  EXPECT_TRUE(std::isnan(nan_mesh.vertices(2, 1)));
  expect_error([&] { validate_mesh(nan_mesh, "nan_vertex.obj"); }, Status::invalid_mesh,
               {"nan_vertex.obj: vertex 2 has a non-finite coordinate (nan)"});

  const TriangleMesh fin = read_mesh(data_file("non_manifold.off"));
  EXPECT_EQ(fin.num_faces(), 3);
  expect_error([&] { validate_mesh(fin, "non_manifold.off"); }, Status::invalid_mesh,
               {"non_manifold.off: edge (0, 1) is shared by 3 faces (non-manifold)"});
}

TEST_F(MeshIo, RejectsMissingFilesAndUnknownFormats) {
  const std::string missing = (dir_ / "missing.obj").string();
  expect_error([&] { read_mesh(missing); }, Status::io_error, {missing, "no such file"});
  const std::string folder = (dir_ / "folder.off").string();
  fs::create_directory(folder);
  expect_error([&] { read_mesh(folder); }, Status::io_error, {folder});
  const std::string stl = write("mesh.stl", "solid empty\nendsolid empty\n");
  expect_error([&] { read_mesh(stl); }, Status::io_error, {stl, "unknown mesh format '.stl'"});
  expect_error([&] { write_mesh(stl, make_grid(1, 1, 1, 1)); }, Status::io_error,
               {"unknown mesh format"});
  expect_error([&] { read_mesh(write("no_extension", "v 0 0 0\n")); }, Status::io_error,
               {"unknown mesh format"});
}

TEST_F(MeshIo, ReportsUnwritablePaths) {
  const std::string path = (dir_ / "no_such_dir" / "out.obj").string();
  expect_error([&] { write_mesh(path, make_grid(1, 1, 1, 1)); }, Status::io_error, {path});
}

TEST_F(MeshIo, RejectsAnOffHeaderClaimingMoreThanTheFileHolds) {
  // Without the check, the reader would allocate 2e9 points before noticing the missing data.
  const std::string path = write("huge.off", "OFF\n2000000000 1 0\n0 0 0\n3 0 0 0\n");
  expect_error([&] { read_mesh(path); }, Status::io_error, {"huge.off", "2000000000 vertices"});
}

TEST_F(MeshIo, RefusesBinaryAndHigherDimensionalOff) {
  const std::string path = write("binary.off", std::string("OFF BINARY\n") + "\x44\x66\x66\x44");
  expect_error([&] { read_mesh(path); }, Status::io_error, {"binary.off", "binary OFF"});
  const std::string glued = write("glued.off", std::string("OFF BINARY\x0f\n") + "\x44\x66");
  expect_error([&] { read_mesh(glued); }, Status::io_error, {"glued.off", "binary OFF"});
  const std::string four_d = write("4d.off", "4OFF\n1 0 0\n0 0 0 1\n");
  expect_error([&] { read_mesh(four_d); }, Status::io_error,
               {"4d.off: cannot parse the file as OFF (line 1", "'4OFF'", "not supported"});
}

TEST_F(MeshIo, RejectsAnOffFileWithoutItsKeyword) {
  // Found by the fuzzer: a control byte glued to the keyword ("\x02OFF\x08") reached
  // undefined behaviour in CGAL's OFF scanner.
  const std::string path = write("glued_keyword.off", "\x02OFF\x083 1 0\n0 0 0\n1 0 0\n0 1 0\n");
  expect_error([&] { read_mesh(path); }, Status::io_error,
               {"glued_keyword.off: cannot parse the file as OFF (line 1",
                "does not start with the keyword OFF"});
}

TEST_F(MeshIo, ReadsOffVariantsAndIgnoresTheEdgeCountAndExtraValues) {
  // The edge count is unused (CGAL doubled it in an int: a fuzzer finding); colours and
  // normals after the coordinates and the face indices are skipped; counts may follow the
  // keyword on its line; nan reaches validate_mesh.
  const std::string path = write("variants.off",
                                 "CNOFF 3 1 1147495276 # counts on the keyword line\n"
                                 "0 0 0  0 0 1  255 0 0\n"
                                 "+1 0 0 0 0 1  0 255 0\n"
                                 "0 nan 0 0 0 1  0 0 255\n"
                                 "3 0 1 2  0.5 0.5 0.5\n");
  const TriangleMesh mesh = read_mesh(path);
  ASSERT_EQ(mesh.num_vertices(), 3);
  ASSERT_EQ(mesh.num_faces(), 1);
  EXPECT_EQ(mesh.vertices(1, 0), 1.0);
  EXPECT_TRUE(std::isnan(mesh.vertices(2, 1)));
  EXPECT_EQ(mesh.faces(0, 2), 2);
}

TEST_F(MeshIo, NamesTheLineOfAMalformedOffFile) {
  const std::string truncated = write("truncated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n");
  expect_error(
      [&] { read_mesh(truncated); }, Status::io_error,
      {"truncated.off: cannot parse the file as OFF (line 4", "before vertex 2", "truncated"});
  const std::string bad_number = write("bad_number.off", "OFF\n3 1 0\n0 0 0\n1 0x 0\n0 1 0\n");
  expect_error([&] { read_mesh(bad_number); }, Status::io_error,
               {"(line 4: vertex 1 coordinate '0x' is not a number"});
  const std::string short_face = write("short_face.off", "OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
  expect_error([&] { read_mesh(short_face); }, Status::io_error,
               {"(line 6: face 0 declares 3 vertices but lists 2"});
  const std::string bad_counts = write("bad_counts.off", "OFF\n3 -1 0\n");
  expect_error([&] { read_mesh(bad_counts); }, Status::io_error,
               {"(line 2: expected the counts '|V| |F| [|E|]' as whole numbers"});
}

TEST_F(MeshIo, NeverCrashesOnTruncatedOrScrambledFiles) {
  // Every prefix length class and random byte flips of valid files: read_mesh either returns
  // a mesh whose indices are in range or throws progsim::Error, nothing else.
  const TriangleMesh mesh = make_sphere(1.0, 1);
  std::mt19937 rng(7);
  for (const std::string ext : {".obj", ".off", ".ply"}) {
    const fs::path source = dir_ / ("source" + ext);
    write_mesh(source.string(), mesh);
    const std::string text = file_text(source);
    for (int trial = 0; trial < 60; ++trial) {
      std::string damaged = text.substr(0, rng() % text.size());
      if (trial % 2 == 1 && !damaged.empty())
        for (int flip = 0; flip < 8; ++flip)
          damaged[rng() % damaged.size()] = static_cast<char>(rng() % 256);
      const std::string path = write("damaged" + ext, damaged);
      SCOPED_TRACE(ext + " trial " + std::to_string(trial));
      try {
        const TriangleMesh read = read_mesh(path);
        if (read.num_faces() > 0) {
          EXPECT_GE(read.faces.minCoeff(), 0);
          EXPECT_LT(read.faces.maxCoeff(), read.num_vertices());
        }
      } catch (const Error& e) {
        EXPECT_TRUE(e.status() == Status::io_error || e.status() == Status::invalid_mesh)
            << e.what();
      }
    }
  }
}
