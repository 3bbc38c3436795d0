// The contact barrier and lagged friction as energy terms: gradients and Hessians against
// finite differences on two-triangle configurations of every distance type (including nearly
// parallel edges and a point near an edge), with and without thickness offsets; the ground;
// PSD projection; +∞ inside the offset; and the broad phase against brute force.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "contact/broad_phase.hpp"
#include "contact/contact_potential.hpp"
#include "contact/friction_potential.hpp"
#include "mesh/mesh_generators.hpp"
#include "support/energy_checks.hpp"

using namespace progsim;
namespace pt = progsim::test_support;

namespace {

constexpr double kDhat = 1e-2;

/// Two separate triangles: A = (0, 1, 2) in the plane z = 0, B = (3, 4, 5) given.
struct TwoTriangles {
  Positions x;
  Faces faces;
};

TwoTriangles two_triangles(const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  TwoTriangles t;
  t.x.resize(6, 3);
  t.x << 0, 0, 0, 1, 0, 0, 0, 1, 0, b0.transpose(), b1.transpose(), b2.transpose();
  t.faces.resize(2, 3);
  t.faces << 0, 1, 2, 3, 4, 5;
  return t;
}

ContactPotential make_contact(const TwoTriangles& t, double offset,
                              std::optional<GroundPlane> ground = std::nullopt) {
  return ContactPotential(build_collision_mesh(t.x, t.faces, std::vector<double>(6, offset),
                                               std::vector<double>(6, 0.5), {}),
                          kDhat, 3.0, ground);
}

/// The configurations: name and triangle B (A is fixed in z = 0).
std::vector<std::pair<std::string, TwoTriangles>> configurations(double gap) {
  return {
      // vertex 3 above A's interior: point–triangle
      {"point_triangle", two_triangles({0.3, 0.3, gap}, {0.5, 0.3, 0.5}, {0.3, 0.6, 0.5})},
      // vertex 3 just outside A's hypotenuse, slightly above: point–edge
      {"point_edge", two_triangles({0.5025, 0.5025, gap}, {1.0, 1.0, 0.4}, {0.6, 1.2, 0.3})},
      // edge (3, 4) crossing over A's edge (0, 1) at right angles: edge–edge
      {"edge_edge", two_triangles({0.5, -0.3, gap}, {0.5, 0.3, gap}, {0.5, 0.0, 0.6})},
      // edge (3, 4) nearly parallel to A's edge (0, 1) and above it: mollified edge–edge
      {"parallel_edges", two_triangles({0.2, -1e-3, gap}, {0.8, 1e-3, gap}, {0.5, -0.2, 0.5})},
  };
}

void expect_matches_finite_differences(EnergyTerm& term, const Vector& x, double step) {
  const Vector g = pt::analytic_gradient(term, x);
  const Vector g_fd = pt::finite_difference_gradient(term, x, step);
  EXPECT_LT(pt::relative_error(g, g_fd, 1e-9), 1e-5) << "gradient";
  const Eigen::MatrixXd h = pt::assembled_hessian(term, x, false);
  const Eigen::MatrixXd h_fd = pt::finite_difference_hessian(term, x, step);
  EXPECT_LT(pt::relative_error(h, h_fd, 1e-9), 1e-4) << "Hessian";
}

}  // namespace

TEST(ContactPotential, DerivativesMatchFiniteDifferencesForEveryDistanceType) {
  for (double offset : {0.0, 2e-3}) {
    for (auto& [name, t] : configurations(2.0 * offset + 0.4 * kDhat)) {
      SCOPED_TRACE(name + " offset " + std::to_string(offset));
      ContactPotential contact = make_contact(t, offset);
      const Vector x = as_dofs(t.x);
      contact.begin_solve(x);
      ASSERT_GT(contact.value(x), 0.0) << "the pair must be inside the barrier's range";
      expect_matches_finite_differences(contact, x, 1e-8);
    }
  }
}

TEST(ContactPotential, AVertexNearestAMeshVertexOrEdgeCountsEveryFaceAroundIt) {
  // A pyramid of six faces around its apex, vertex 0, and a triangle whose vertex 7 is near
  // it: above the apex every face's pair is the same vertex–vertex barrier, off the middle of
  // a ridge both faces' pairs are the same vertex–edge barrier (robustly: the pyramid is
  // convex there). Each is evaluated once and counted per face (IPC Toolkit's weights); the
  // value sums every pair. Against FD of it.
  Positions x(10, 3);
  x.row(0) << 0.0, 0.0, 0.2;
  for (int k = 0; k < 6; ++k) x.row(1 + k) << std::cos(k * kPi / 3), std::sin(k * kPi / 3), 0.0;
  Faces faces(7, 3);
  for (int k = 0; k < 6; ++k) faces.row(k) << 0, 1 + k, 1 + (k + 1) % 6;
  faces.row(6) << 7, 8, 9;
  const Vec3 ridge_middle(0.5, 0.0, 0.1), ridge_normal = Vec3(0.2, 0.0, 1.0).normalized();
  for (const Vec3& near :
       {Vec3(0, 0, 0.2 + 0.4 * kDhat), Vec3(ridge_middle + 0.3 * kDhat * ridge_normal)}) {
    x.row(7) = near.transpose();
    x.row(8) = (near + Vec3(0.3, 0.1, 0.4)).transpose();
    x.row(9) = (near + Vec3(-0.1, 0.3, 0.5)).transpose();
    ContactPotential contact(build_collision_mesh(x, faces, std::vector<double>(10, 0.0),
                                                  std::vector<double>(10, 0.5), {}),
                             kDhat, 3.0, std::nullopt);
    const Vector dofs = as_dofs(x);
    contact.begin_solve(dofs);
    ASSERT_GT(contact.value(dofs), 0.0);
    expect_matches_finite_differences(contact, dofs, 1e-8);
  }
}

TEST(ContactPotential, MeasuresThePairsAgainWhenTheCandidatesChange) {
  // Distances measured at x are reused at the same x only while the candidates stay. B's edge
  // (3, 4) crosses over A's edge (0, 1) within d̂; a CCD query at x that brings vertex 5 down
  // to A adds vertex–face candidates ahead of the edge–edge ones. The gradient at x must then
  // still be that of a potential that never saw the query.
  const double gap = 0.4 * kDhat;
  const TwoTriangles t = two_triangles({0.5, -0.3, gap}, {0.5, 0.3, gap}, {0.5, 0.0, 0.6});
  const Vector x = as_dofs(t.x);
  ContactPotential queried = make_contact(t, 0.0), fresh = make_contact(t, 0.0);
  queried.begin_solve(x);
  fresh.begin_solve(x);
  ASSERT_NE(pt::analytic_gradient(queried, x), Vector::Zero(x.size()));
  Vector down = Vector::Zero(x.size());
  down(3 * 5 + 2) = -0.6;
  queried.max_step(x, down);
  EXPECT_EQ(queried.value(x), fresh.value(x));
  EXPECT_EQ(pt::analytic_gradient(queried, x), pt::analytic_gradient(fresh, x));
}

TEST(ContactPotential, MovingVerticesLeaveOutOnlyPairsOfStillOnes) {
  // Triangle A in z = 0, B and C each with a vertex just above it, far from each other. With
  // only C moving, the energy loses B's pair, a constant as C moves; C's forces are unchanged.
  Positions x(9, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0,                    // A
      0.3, 0.3, 4e-3, 0.5, 0.3, 0.5, 0.3, 0.6, 0.5,  // B
      0.7, 0.1, 3e-3, 0.9, 0.1, 0.5, 0.7, 0.2, 0.5;  // C
  Faces faces(3, 3);
  faces << 0, 1, 2, 3, 4, 5, 6, 7, 8;
  const CollisionMesh mesh =
      build_collision_mesh(x, faces, std::vector<double>(9, 0.0), std::vector<double>(9, 0.0), {});
  ContactPotential full(mesh, kDhat, 3.0, std::nullopt), only_c(mesh, kDhat, 3.0, std::nullopt);
  only_c.set_moving_vertices({0, 0, 0, 0, 0, 0, 1, 1, 1});
  const auto energy_gap = [&](const Vector& dofs) {
    full.begin_solve(dofs);
    only_c.begin_solve(dofs);
    return full.value(dofs) - only_c.value(dofs);
  };
  Vector dofs = as_dofs(x);
  const double left_out = energy_gap(dofs);
  EXPECT_GT(left_out, 0.0);            // B's pair
  EXPECT_GT(only_c.value(dofs), 0.0);  // C's pair
  Vector g_full = Vector::Zero(27), g_c = Vector::Zero(27);
  full.add_gradient(dofs, g_full);
  only_c.add_gradient(dofs, g_c);
  EXPECT_LT((g_full.tail(9) - g_c.tail(9)).norm(), 1e-12 * g_full.tail(9).norm());
  EXPECT_GT(g_full.tail(9).norm(), 0.0);
  dofs[20] -= 1e-3;  // C's vertex closer to A
  EXPECT_NEAR(energy_gap(dofs), left_out, 1e-12 * left_out);
  EXPECT_THROW(only_c.set_moving_vertices({1, 0}), Error);
}

TEST(ContactPotential, NearlyParallelEdgesAreMollifiedSmoothly) {
  // The mollifier scales the parallel pair's barrier down; its derivatives stay finite.
  auto configs = configurations(0.4 * kDhat);
  ContactPotential parallel = make_contact(configs[3].second, 0.0);
  const Vector x = as_dofs(configs[3].second.x);
  parallel.begin_solve(x);
  const Vector g = pt::analytic_gradient(parallel, x);
  EXPECT_TRUE(g.allFinite());
  EXPECT_TRUE(pt::assembled_hessian(parallel, x, false).allFinite());
}

TEST(ContactPotential, GroundBarrierDerivativesAndCcd) {
  TwoTriangles t = two_triangles({0.3, 0.3, 0.5}, {0.5, 0.3, 0.5}, {0.3, 0.6, 0.5});
  t.x.col(2).head(3).setConstant(0.3 * kDhat);  // triangle A hovering over the ground z = 0
  t.x(1, 2) = 0.7 * kDhat;
  ContactPotential contact = make_contact(t, 0.0, GroundPlane{Vec3::UnitZ(), 0.0, 0.2});
  const Vector x = as_dofs(t.x);
  contact.begin_solve(x);
  ASSERT_GT(contact.value(x), 0.0);
  expect_matches_finite_differences(contact, x, 1e-9);
  // Moving everything 1 m down: CCD stops before the ground, keeping ≥ 10% of the gap.
  Vector down = Vector::Zero(x.size());
  for (int v = 0; v < 6; ++v) down[3 * v + 2] = -1.0;
  const double alpha = contact.max_step(x, down);
  EXPECT_GT(alpha, 0.0);
  EXPECT_LE(alpha, 0.9 * 0.3 * kDhat + 1e-15);
  EXPECT_TRUE(std::isfinite(contact.value(x + alpha * down)));
  // A non-finite motion has no safe step (issue 33 §7): NaN, never the whole step.
  down[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(contact.max_step(x, down)));
  down[4] = 0.0;
  down[2] = std::numeric_limits<double>::infinity();  // an infinite entry too
  EXPECT_TRUE(std::isnan(contact.max_step(x, down)));
}

TEST(ContactPotential, InfiniteInsideTheOffsetAndZeroBeyondTheGap) {
  auto configs = configurations(0.0);
  TwoTriangles touching = configs[0].second;
  touching.x(3, 2) = 1e-3;  // vertex 3 is 1 mm above A, inside a 2 + 2 mm offset
  ContactPotential thick = make_contact(touching, 2e-3);
  const Vector x = as_dofs(touching.x);
  thick.begin_solve(x);
  EXPECT_EQ(thick.value(x), std::numeric_limits<double>::infinity());
  EXPECT_THROW(thick.check_separated(x), Error);
  TwoTriangles apart = configs[0].second;
  apart.x(3, 2) = 2.0 * kDhat;
  ContactPotential thin = make_contact(apart, 0.0);
  thin.begin_solve(as_dofs(apart.x));
  EXPECT_EQ(thin.value(as_dofs(apart.x)), 0.0);
  EXPECT_NO_THROW(thin.check_separated(as_dofs(apart.x)));
}

TEST(ContactPotential, ProjectedHessianIsPositiveSemidefinite) {
  for (auto& [name, t] : configurations(0.2 * kDhat)) {
    SCOPED_TRACE(name);
    ContactPotential contact = make_contact(t, 0.0);
    const Vector x = as_dofs(t.x);
    contact.begin_solve(x);
    const Eigen::MatrixXd h = pt::assembled_hessian(contact, x, true);
    EXPECT_GT(pt::eigenvalues(h).minCoeff(), -1e-9 * h.cwiseAbs().maxCoeff());
  }
}

TEST(ContactPotential, RejectsNonsenseParameters) {
  const TwoTriangles t = configurations(0.5)[0].second;
  auto mesh = build_collision_mesh(t.x, t.faces, std::vector<double>(6, 0.0),
                                   std::vector<double>(6, 0.0), {});
  EXPECT_THROW(ContactPotential(mesh, 0.0, 1.0, std::nullopt), Error);
  EXPECT_THROW(ContactPotential(mesh, -1.0, 1.0, std::nullopt), Error);
  EXPECT_THROW(ContactPotential(mesh, 1e-3, 0.0, std::nullopt), Error);
  EXPECT_THROW(ContactPotential(mesh, std::nan(""), 1.0, std::nullopt), Error);
}

TEST(FrictionPotential, DerivativesMatchFiniteDifferencesSlidingAndSticking) {
  for (auto& [name, t] : configurations(0.4 * kDhat)) {
    ContactPotential contact = make_contact(t, 0.0);
    const Vector x0 = as_dofs(t.x);
    contact.begin_solve(x0);
    const double epsilon = 1e-4;
    FrictionPotential friction(contact, epsilon);
    friction.lag(x0);
    ASSERT_GT(friction.num_contacts(), 0) << name;
    for (double slip : {0.3 * epsilon, 20.0 * epsilon}) {  // smoothed (static) and sliding
      SCOPED_TRACE(name + " slip " + std::to_string(slip));
      Vector x = x0;
      for (int v = 3; v < 6; ++v) x.segment<3>(3 * v) += slip * Vec3(0.8, 0.6, 0.0);
      expect_matches_finite_differences(friction, x, 1e-3 * epsilon);
      const Eigen::MatrixXd h = pt::assembled_hessian(friction, x, false);
      EXPECT_GT(pt::eigenvalues(h).minCoeff(), -1e-9 * h.cwiseAbs().maxCoeff()) << "PSD";
    }
  }
}

TEST(FrictionPotential, SlidingForceIsCoulombsMuTimesTheNormalForce) {
  // A vertex over the ground slides by much more than ε: |friction force| = μ λ, opposing it.
  TwoTriangles t = configurations(0.5)[0].second;  // B far above A
  t.x.col(2).head(3).setConstant(0.5 * kDhat);
  ContactPotential contact = make_contact(t, 0.0, GroundPlane{Vec3::UnitZ(), 0.0, 0.5});
  const Vector x0 = as_dofs(t.x);
  contact.begin_solve(x0);
  FrictionPotential friction(contact, 1e-6);
  friction.lag(x0);
  ASSERT_EQ(friction.num_contacts(), 3);
  Vector x = x0;
  for (int v = 0; v < 3; ++v) x[3 * v] += 1e-3;  // slide triangle A along +x
  Vector g = Vector::Zero(x.size());
  friction.add_gradient(x, g);
  // μ = √(0.5 · 0.5); λ from the barrier: 2 κ |b'(s)| d at d = 0.5 d̂.
  Vector barrier_gradient = Vector::Zero(x.size());
  contact.add_gradient(x0, barrier_gradient);
  for (int v = 0; v < 3; ++v) {
    const double normal_force = std::abs(barrier_gradient[3 * v + 2]);
    EXPECT_NEAR(g[3 * v], 0.5 * normal_force, 1e-9 * normal_force) << "vertex " << v;
    EXPECT_NEAR(g[3 * v + 1], 0.0, 1e-12);
  }
}

/// Broad-phase cases: with a spike (a few primitives far larger than the grid cell, the
/// "large" path) and with a second obstacle 10 km away (the grid's region then has too many
/// cells to store densely: the hashed path).
struct BroadPhaseCase {
  bool spike;
  bool far_obstacle;
};

class BroadPhase : public ::testing::TestWithParam<BroadPhaseCase> {};

TEST_P(BroadPhase, FindsEveryPairWithinTheGapLikeBruteForce) {
  // A crumpled sheet moving over a sphere obstacle: every vertex–face and edge–edge pair whose
  // swept boxes overlap, by brute force, except pairs sharing a vertex or of two obstacles.
  TriangleMesh sheet = make_grid(1.0, 1.0, 8, 8);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.08, 0.08);
  for (Eigen::Index i = 0; i < sheet.vertices.rows(); ++i)
    sheet.vertices(i, 2) = noise(rng) + 0.3 * std::sin(6.0 * sheet.vertices(i, 0));
  if (GetParam().spike) sheet.vertices.row(40) += Vec3(2.0, 2.0, 3.0).transpose();  // > 64 cells
  TriangleMesh sphere = make_sphere(0.3, 1);
  sphere.vertices.col(0).array() += 0.5;
  sphere.vertices.col(1).array() += 0.5;
  sphere.vertices.col(2).array() -= 0.2;
  TriangleMesh far = make_sphere(0.3, 0);
  far.vertices.array() += 1e4;
  std::vector<ObstacleSurface> obstacles{{&sphere.vertices, &sphere.faces, 0.0}};
  if (GetParam().far_obstacle) obstacles.push_back({&far.vertices, &far.faces, 0.0});
  const auto mesh = build_collision_mesh(sheet.vertices, sheet.faces,
                                         std::vector<double>(sheet.num_vertices(), 0.0),
                                         std::vector<double>(sheet.num_vertices(), 0.0), obstacles);
  Positions p1 = mesh.rest;
  for (int v = 0; v < mesh.num_shell_vertices; ++v)
    p1.row(v) += Vec3(0.03 * noise(rng), 0.03 * noise(rng), -0.1).transpose();
  CandidateSet found;
  const double inflation = 0.05;
  find_candidates(mesh, mesh.rest, p1, inflation, found);
  auto box_gap = [&](std::initializer_list<int> a, std::initializer_list<int> b) {
    double gap = 0.0;  // largest per-axis separation of the two primitives' swept boxes
    for (int k = 0; k < 3; ++k) {
      double alo = 1e9, ahi = -1e9, blo = 1e9, bhi = -1e9;
      for (const Positions* p : {&mesh.rest, const_cast<const Positions*>(&p1)}) {
        for (int v : a) alo = std::min(alo, (*p)(v, k)), ahi = std::max(ahi, (*p)(v, k));
        for (int v : b) blo = std::min(blo, (*p)(v, k)), bhi = std::max(bhi, (*p)(v, k));
      }
      gap = std::max(gap, std::max(blo - ahi, alo - bhi));
    }
    return gap;
  };
  // Found: every pair within the gap, and no pair beyond it (up to rounding at the boundary),
  // none twice.
  const double sure = inflation * (1.0 - 1e-9), at_most = inflation * (1.0 + 1e-9);
  std::size_t obstacle_pairs = 0, edge_pairs = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    for (int f = 0; f < mesh.faces.rows(); ++f) {
      const auto face = mesh.faces.row(f);
      if (face[0] == v || face[1] == v || face[2] == v) continue;
      if (mesh.is_obstacle(v) && mesh.is_obstacle(face[0])) continue;
      if (box_gap({v}, {face[0], face[1], face[2]}) > sure) continue;
      obstacle_pairs += mesh.is_obstacle(v) || mesh.is_obstacle(face[0]);
      EXPECT_TRUE(std::binary_search(found.vertex_face.begin(), found.vertex_face.end(),
                                     std::array<int, 2>{v, f}));
    }
  for (std::size_t a = 0; a < mesh.edges.size(); ++a)
    for (std::size_t b = a + 1; b < mesh.edges.size(); ++b) {
      const auto& ea = mesh.edges[a];
      const auto& eb = mesh.edges[b];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
      if (mesh.is_obstacle(ea[0]) && mesh.is_obstacle(eb[0])) continue;
      if (box_gap({ea[0], ea[1]}, {eb[0], eb[1]}) > sure) continue;
      ++edge_pairs;
      EXPECT_TRUE(std::binary_search(found.edge_edge.begin(), found.edge_edge.end(),
                                     std::array<int, 2>{static_cast<int>(a), static_cast<int>(b)}));
    }
  for (const auto& [v, f] : found.vertex_face) {
    const auto face = mesh.faces.row(f);
    EXPECT_LE(box_gap({v}, {face[0], face[1], face[2]}), at_most) << v << ", " << f;
    EXPECT_FALSE(mesh.is_obstacle(v) && mesh.is_obstacle(face[0]));
  }
  for (const auto& [a, b] : found.edge_edge) {
    EXPECT_LT(a, b);
    EXPECT_LE(box_gap({mesh.edges[a][0], mesh.edges[a][1]}, {mesh.edges[b][0], mesh.edges[b][1]}),
              at_most);
    EXPECT_FALSE(mesh.is_obstacle(mesh.edges[a][0]) && mesh.is_obstacle(mesh.edges[b][0]));
  }
  EXPECT_EQ(std::adjacent_find(found.vertex_face.begin(), found.vertex_face.end()),
            found.vertex_face.end());
  EXPECT_EQ(std::adjacent_find(found.edge_edge.begin(), found.edge_edge.end()),
            found.edge_edge.end());
  EXPECT_GT(edge_pairs, 0u);
  EXPECT_GT(obstacle_pairs, 0u);  // the sheet reaches the sphere
  // With a third of the vertices moving (obstacle ones too), exactly the pairs that touch one.
  std::vector<char> moving(mesh.num_vertices(), 0);
  for (int v = 0; v < mesh.num_vertices(); ++v) moving[v] = rng() % 3 == 0;
  const auto touches_moving = [&](std::initializer_list<int> vertices) {
    for (int v : vertices)
      if (moving[v]) return true;
    return false;
  };
  CandidateSet expected, masked;
  for (const auto& [v, f] : found.vertex_face)
    if (touches_moving({v, mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)}))
      expected.vertex_face.push_back({v, f});
  for (const auto& [a, b] : found.edge_edge)
    if (touches_moving({mesh.edges[a][0], mesh.edges[a][1], mesh.edges[b][0], mesh.edges[b][1]}))
      expected.edge_edge.push_back({a, b});
  find_candidates(mesh, mesh.rest, p1, inflation, masked, &moving);
  EXPECT_EQ(masked.vertex_face, expected.vertex_face);
  EXPECT_EQ(masked.edge_edge, expected.edge_edge);
  EXPECT_LT(masked.size(), found.size());
  EXPECT_GT(masked.size(), 0u);
  moving.pop_back();
  EXPECT_THROW(find_candidates(mesh, mesh.rest, p1, inflation, masked, &moving), Error);
}

INSTANTIATE_TEST_SUITE_P(WithLargeBoxesAndFarObstacles, BroadPhase,
                         ::testing::Values(BroadPhaseCase{false, false},
                                           BroadPhaseCase{true, false}, BroadPhaseCase{false, true},
                                           BroadPhaseCase{true, true}));

TEST(ContactPotential, FitOffsetsLowersOnlyThePairsInsideAndRaisesThemBack) {
  auto configs = configurations(0.0);
  TwoTriangles touching = configs[0].second;
  touching.x(3, 2) = 1e-3;  // vertex 3 is 1 mm above A: inside the 2 + 2 mm offset
  ContactPotential contact = make_contact(touching, 2e-3);
  Vector x = as_dofs(touching.x);
  EXPECT_GT(contact.fit_offsets(x), 0);
  contact.begin_solve(x);
  EXPECT_TRUE(std::isfinite(contact.value(x)));  // the lowered pair is outside its offset now
  EXPECT_NO_THROW(contact.check_separated(x));
  EXPECT_LT(contact.stats().min_gap, 1e-3);  // … by its 80% of 1 mm, not by its full 4 mm
  // Opened to 3 mm, the pair's offset rises halfway (0.8 → 1.9 mm), still below 4 mm; opened
  // to 8 mm it would rise to 4.95 mm: the full 4 mm holds again and nothing stays lowered.
  x[3 * 3 + 2] = 3e-3;
  EXPECT_GT(contact.fit_offsets(x), 0);
  x[3 * 3 + 2] = 8e-3;
  EXPECT_EQ(contact.fit_offsets(x), 0);
  EXPECT_EQ(contact.reduced_offsets(), 0);
  contact.begin_solve(x);
  EXPECT_NO_THROW(contact.check_separated(x));
  x[3 * 3 + 2] = 3e-3;  // back inside the full offset: +∞ again
  contact.begin_solve(x);
  EXPECT_EQ(contact.value(x), std::numeric_limits<double>::infinity());
}
