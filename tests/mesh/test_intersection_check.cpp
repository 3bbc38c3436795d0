// The exact intersection check against configurations whose answer is known by construction.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "mesh/intersection_check.hpp"
#include "mesh/mesh_generators.hpp"

using namespace progsim;

namespace {

/// Two unit grids: the second translated by `offset` (merged into one mesh, as bodies are).
TriangleMesh two_sheets(const Vec3& offset, double angle_about_x) {
  const TriangleMesh sheet = make_grid(1.0, 1.0, 4, 4);
  TriangleMesh both;
  const int n = sheet.num_vertices();
  both.vertices.resize(2 * n, 3);
  both.faces.resize(2 * sheet.num_faces(), 3);
  const Eigen::AngleAxisd rotation(angle_about_x, Vec3::UnitX());
  for (int v = 0; v < n; ++v) {
    both.vertices.row(v) = sheet.vertices.row(v);
    both.vertices.row(n + v) =
        (rotation * Vec3(sheet.vertices.row(v).transpose()) + offset).transpose();
  }
  both.faces.topRows(sheet.num_faces()) = sheet.faces;
  both.faces.bottomRows(sheet.num_faces()) = sheet.faces.array() + n;
  return both;
}

}  // namespace

TEST(IntersectionCheck, AcceptsIntersectionFreeConfigurations) {
  const TriangleMesh sphere = make_sphere(1.0, 2);
  EXPECT_TRUE(intersecting_faces(sphere.vertices, sphere.faces).empty());
  const TriangleMesh parallel = two_sheets(Vec3(0.2, 0.1, 1e-9), 0.0);  // 1 nm apart
  EXPECT_TRUE(intersecting_faces(parallel.vertices, parallel.faces).empty());
  EXPECT_NO_THROW(check_intersection_free(parallel.vertices, parallel.faces, "sheets"));
}

TEST(IntersectionCheck, FindsSheetsPiercingEachOther) {
  // The second sheet stands upright (rotated 90° about x) through the first one's middle.
  const TriangleMesh crossing = two_sheets(Vec3(0.13, 0.5, -0.5), 1.5707963267948966);
  const std::vector<FacePair> pairs = intersecting_faces(crossing.vertices, crossing.faces);
  ASSERT_FALSE(pairs.empty());
  for (const FacePair& p : pairs) {
    EXPECT_LT(p.a, 32) << "one face of each pair is in the first sheet";
    EXPECT_GE(p.b, 32);
  }
  EXPECT_EQ(intersecting_faces(crossing.vertices, crossing.faces, 1).size(), 1u);
  try {
    check_intersection_free(crossing.vertices, crossing.faces, "scene");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::intersecting);
    EXPECT_NE(std::string(e.what()).find("scene: faces "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(" intersect"), std::string::npos) << e.what();
  }
}

TEST(IntersectionCheck, FindsAFoldThroughANeighbour) {
  // Push one vertex of a flat grid far through the sheet so that its faces cross faces
  // that share no vertex with them; and check a crumpled but non-crossing sheet passes.
  TriangleMesh sheet = make_grid(1.0, 1.0, 6, 6);
  sheet.vertices(24, 2) = 0.05;  // a bump: no intersection
  EXPECT_TRUE(intersecting_faces(sheet.vertices, sheet.faces).empty());
  // Fold the top half down under the bottom half: rows y > 0.5 mirrored to z < 0 and
  // shifted back over the bottom half, crossing it.
  for (int v = 0; v < sheet.num_vertices(); ++v)
    if (sheet.vertices(v, 1) > 0.5 + 1e-9) {
      const double d = sheet.vertices(v, 1) - 0.5;
      sheet.vertices(v, 1) = 0.5 - d * 0.9;
      sheet.vertices(v, 2) = (v % 2 == 0 ? 0.02 : -0.02);  // weaves through the lower half
    }
  EXPECT_FALSE(intersecting_faces(sheet.vertices, sheet.faces).empty());
}
