// Vertices no collision face uses (a solid's interior) are DOFs without contact: they never
// meet a face in the broad phase and have no ground pair.
#include <gtest/gtest.h>

#include "contact/broad_phase.hpp"
#include "contact/collision_mesh.hpp"

using namespace progsim;

TEST(CollisionPoints, VerticesNoFaceUsesNeverCollide) {
  // Two triangles far apart, and vertex 6 (no face) lying on triangle 0, vertex 7 on triangle 1.
  Positions p(8, 3);
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
      0, 0, 5, 1, 0, 5, 0, 1, 5,   //
      0.2, 0.2, 0.0, 0.2, 0.2, 5.0;
  Faces f(2, 3);
  f << 0, 1, 2, 3, 4, 5;
  const CollisionMesh mesh =
      build_collision_mesh(p, f, std::vector<double>(8, 0.0), std::vector<double>(8, 0.0), {});
  EXPECT_EQ(mesh.points, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(mesh.num_shell_points, 6);
  CandidateSet all, moving;
  find_candidates(mesh, p, p, 0.1, all);
  std::vector<char> flags(8, 1);
  find_candidates(mesh, p, p, 0.1, moving, &flags);
  for (const CandidateSet* c : {&all, &moving}) {
    EXPECT_TRUE(c->vertex_face.empty());  // 6 and 7 touch faces but are no contact points
    EXPECT_TRUE(c->edge_edge.empty());
  }
}
