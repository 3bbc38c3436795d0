// Tet mesh validation: valid meshes pass; each kind of defect, in a hand-written file of
// tests/data/tet/ or built here, is rejected as invalid_mesh with a message naming it.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh/tet_generators.hpp"
#include "mesh/tet_mesh_io.hpp"
#include "mesh/tet_mesh_validation.hpp"
#include "mesh_test_support.hpp"
#include "tet_test_support.hpp"

using namespace progsim;
using progsim::test_support::expect_error;
using progsim::tet_test::cube5;
using progsim::tet_test::tet_data;
using progsim::tet_test::unit_tet;

namespace {

/// Expects validate_tet_mesh on `mesh` to throw invalid_mesh naming the label and `parts`.
void expect_invalid_tets(const TetMesh& mesh, std::initializer_list<std::string> parts) {
  expect_error([&] { validate_tet_mesh(mesh, "my mesh"); }, Status::invalid_mesh, {"my mesh: "});
  expect_error([&] { validate_tet_mesh(mesh, "my mesh"); }, Status::invalid_mesh, parts);
}

/// Expects the data file `name` to read but fail validation naming `parts`.
void expect_invalid_tet_file(const std::string& name, std::initializer_list<std::string> parts) {
  const TetMesh mesh = read_tet_mesh(tet_data(name));
  expect_invalid_tets(mesh, parts);
}

}  // namespace

TEST(TetMeshValidation, ValidMeshesPass) {
  EXPECT_NO_THROW(validate_tet_mesh(unit_tet(), "unit tet"));
  EXPECT_NO_THROW(validate_tet_mesh(cube5(), "cube"));
  EXPECT_NO_THROW(validate_tet_mesh(make_tet_box(Vec3(1, 2, 3), 3, 2, 1), "box"));
  // A sliver: tiny volume relative to its edges, but far above the tolerance.
  TetMesh sliver = unit_tet();
  sliver.vertices(3, 2) = 1e-6;
  EXPECT_NO_THROW(validate_tet_mesh(sliver, "sliver"));
}

TEST(TetMeshValidation, EmptyMesh) {
  TetMesh mesh = unit_tet();
  mesh.tets.resize(0, 4);
  expect_invalid_tets(mesh, {"no tets", "4 vertices"});
}

TEST(TetMeshValidation, NonFiniteCoordinate) {
  expect_invalid_tet_file("bad_nan.mesh", {"vertex 2", "non-finite"});
  TetMesh mesh = unit_tet();
  mesh.vertices(3, 0) = INFINITY;
  expect_invalid_tets(mesh, {"vertex 3", "non-finite"});
}

TEST(TetMeshValidation, IndexOutOfRange) {
  TetMesh mesh = cube5();
  mesh.tets(2, 1) = 8;
  expect_invalid_tets(mesh, {"tet 2 references vertex 8", "8 vertices"});
  mesh.tets(2, 1) = -1;
  expect_invalid_tets(mesh, {"tet 2 references vertex -1"});
}

TEST(TetMeshValidation, RepeatedVertex) {
  TetMesh mesh = cube5();
  mesh.tets.row(3) << 6, 4, 6, 7;
  expect_invalid_tets(mesh, {"tet 3 repeats a vertex", "(6, 4, 6, 7)"});
}

TEST(TetMeshValidation, InvertedTet) {
  expect_invalid_tet_file("bad_inverted.mesh", {"tet 0 (0, 2, 1, 3) is inverted", "-0.1666"});
}

TEST(TetMeshValidation, DegenerateTet) {
  expect_invalid_tet_file("bad_degenerate.mesh", {"tet 0", "is degenerate"});
}

TEST(TetMeshValidation, DuplicateTet) {
  expect_invalid_tet_file("bad_duplicate.mesh", {"tets 4 and 5 are duplicates"});
}

TEST(TetMeshValidation, FaceSharedByThreeTets) {
  expect_invalid_tet_file("bad_three_tets_on_face.mesh",
                          {"face (0, 1, 2) is shared by 3 tets", "0, 1, 2", "non-manifold"});
}

TEST(TetMeshValidation, TetsOnTheSameSideOfTheirSharedFace) {
  expect_invalid_tet_file("bad_same_side.mesh",
                          {"tets 0 and 1 traverse face (0, 1, 2) in the same orientation"});
}

TEST(TetMeshValidation, CubesSharingOnlyAnEdge) {
  expect_invalid_tet_file("bad_two_cubes_on_edge.mesh",
                          {"edge (3, 7) lies on 4 boundary faces", "not a closed 2-manifold"});
}

TEST(TetMeshValidation, TetsSharingOnlyAVertex) {
  expect_invalid_tet_file("bad_bow_tie.mesh", {"vertex 0", "bow-tie"});
}

TEST(TetMeshValidation, UnreferencedVertex) {
  expect_invalid_tet_file("bad_unreferenced.mesh", {"vertex 4 is not referenced by any tet"});
}
