// Real meshes nobody here wrote (DESIGN.md §4): CGAL's data set from Debian's libcgal-demo,
// fetched by scripts/fetch_test_meshes.sh into $PROGSIM_MESH_CACHE (default
// $HOME/.cache/progsim/meshes). Good models read, validate and have the topology of their
// shapes; CGAL's deliberately broken models (shuffled orientations, degenerate or polygonal
// faces) are rejected with the right reason.
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "mesh/mesh_io.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/off_reader.hpp"
#include "mesh_test_support.hpp"
#include "support/real_meshes.hpp"

using namespace progsim;
using namespace progsim::test_support;
namespace fs = std::filesystem;

namespace {

/// The vertex and face counts in an OFF header, read here independently of CGAL.
std::array<int, 2> off_header_counts(const fs::path& path) {
  std::ifstream in(path);
  std::string keyword;
  int vertices = -1, faces = -1;
  in >> keyword >> vertices >> faces;
  return {vertices, faces};
}

/// A well-formed model and the Euler characteristic and boundary of its shape.
struct GoodMesh {
  const char* file;
  int euler_characteristic;
  int boundary_edges;
};

}  // namespace

class RealMeshes : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_directory(folder_))
        << folder_ << " is missing: run scripts/fetch_test_meshes.sh (set PROGSIM_MESH_CACHE "
        << "to use another cache folder)";
  }

  std::string path(const std::string& file) const { return (folder_ / file).string(); }

  const fs::path folder_ = real_mesh_folder();
};

TEST_F(RealMeshes, WellFormedModelsValidateWithTheTopologyOfTheirShape) {
  const GoodMesh meshes[] = {
      {"sphere.off", 2, 0},     // closed sphere
      {"bunny00.off", 2, 0},    // the Stanford bunny, closed
      {"armadillo.off", 2, 0},  // closed
      {"knot.off", 0, 0},       // a knotted tube: a torus
      {"plane.off", 1, 80},     // a flat sheet with colours (COFF)
      {"mushroom.off", 1, 64},  // an open cap: a disc
  };
  for (const GoodMesh& expected : meshes) {
    SCOPED_TRACE(expected.file);
    const TriangleMesh mesh = read_mesh(path(expected.file));
    const std::array<int, 2> counts = off_header_counts(path(expected.file));
    EXPECT_EQ(mesh.num_vertices(), counts[0]);
    EXPECT_EQ(mesh.num_faces(), counts[1]);
    ASSERT_NO_THROW(validate_mesh(mesh, expected.file));
    const MeshTopology topology = build_topology(mesh.faces, mesh.num_vertices());
    expect_consistent_topology(mesh.faces, topology);
    EXPECT_EQ(euler_characteristic(mesh, topology), expected.euler_characteristic);
    EXPECT_EQ(boundary_edge_count(topology), expected.boundary_edges);
    if (expected.boundary_edges == 0) {
      EXPECT_GT(signed_volume(mesh), 0.0) << "closed models have outward normals";
    }
  }
}

TEST_F(RealMeshes, FlatSheetIsFlat) {
  const TriangleMesh plane = read_mesh(path("plane.off"));
  EXPECT_EQ(plane.vertices.col(1).cwiseAbs().maxCoeff(), 0.0);  // the sheet lies in y = 0
  EXPECT_GT(face_areas(plane.vertices, plane.faces).minCoeff(), 0.0);
}

TEST_F(RealMeshes, SphereReadsTheSameFromOffAndPly) {
  const TriangleMesh off = read_mesh(path("sphere.off"));
  const TriangleMesh ply = read_mesh(path("sphere.ply"));
  EXPECT_EQ(off.vertices, ply.vertices);
  ASSERT_EQ(off.num_faces(), ply.num_faces());
  // The PLY lists each face from another corner: same triangles, same orientation.
  for (int f = 0; f < off.num_faces(); ++f)
    EXPECT_TRUE(face_is(ply.faces, f, off.faces(f, 0), off.faces(f, 1), off.faces(f, 2))) << f;
  for (int v = 0; v < off.num_vertices(); ++v)
    EXPECT_NEAR(off.vertices.row(v).norm(), 0.5, 1e-4) << v;  // 4-digit coordinates
}

TEST_F(RealMeshes, BrokenModelsAreRejectedForTheirReason) {
  const auto expect_invalid = [&](const std::string& file, const std::string& reason) {
    SCOPED_TRACE(file);
    expect_error([&] { validate_mesh(read_mesh(path(file)), file); }, Status::invalid_mesh,
                 {file + ": ", reason});
  };
  // CGAL ships these to test its own repair tools.
  expect_invalid("cube-shuffled.off", "(inconsistent orientation)");
  expect_invalid("tet-shuffled.off", "(inconsistent orientation)");
  expect_invalid("blobby-shuffled.off", "(inconsistent orientation)");
  expect_invalid("degtri_sliding.off", "is degenerate (area 0 m²)");
  expect_invalid("polygon_mesh.off", "(bow-tie)");
  expect_invalid("cube-ouvert.off", "vertex 8 is not referenced by any face");
  expect_invalid("cube_quad.off", "face 0 has 4 vertices");
}

TEST_F(RealMeshes, OurOffReaderAgreesWithCgalsOnEveryOffFileOfTheSet) {
  // read_off replaced CGAL's OFF scanner (undefined behaviour on malformed input); on the
  // well-formed files of CGAL's own data set both must read the same points and polygons.
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  int compared = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder_)) {
    if (entry.path().extension() != ".off") continue;
    SCOPED_TRACE(entry.path().filename().string());
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    if (!CGAL::IO::read_polygon_soup(entry.path().string(), points, polygons,
                                     CGAL::parameters::verbose(false)))
      continue;  // CGAL refuses it too (broken on purpose, or binary)
    const PolygonSoup soup = read_off(entry.path().string());
    ASSERT_EQ(soup.vertices.rows(), static_cast<Eigen::Index>(points.size()));
    for (std::size_t v = 0; v < points.size(); ++v)
      for (int k = 0; k < 3; ++k) ASSERT_EQ(soup.vertices(v, k), points[v][k]) << v;
    EXPECT_EQ(soup.polygons, polygons);
    ++compared;
  }
  EXPECT_GE(compared, 100);  // the set holds over 120 OFF files
}
