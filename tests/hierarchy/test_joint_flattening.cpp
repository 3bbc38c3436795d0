// Joint flattening of edge collapses: patches cut from a triangular lattice (interior edge,
// boundary vertex, border edge, bent and jittered), checked against facts independent of the
// implementation: the regular octagon of a lattice edge's link, central symmetry, before and
// after covering the same polygon, border vertices staying on the circle, non-disk patches
// rejected, and point relocation reproducing the uv of every point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "hierarchy/joint_flattening.hpp"

using namespace progsim;

namespace {

using Face = std::array<int, 3>;

/// A sheared triangular lattice of unit edges, vertex (i, j) at id j * cols + i, faces CCW.
struct Lattice {
  int cols;
  std::vector<Vec3> points;
  std::vector<Face> faces;
  int id(int i, int j) const { return j * cols + i; }
};

Lattice lattice(int cols, int rows) {
  Lattice mesh{cols, {}, {}};
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) mesh.points.emplace_back(i + 0.5 * j, j * std::sqrt(0.75), 0.0);
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      mesh.faces.push_back({mesh.id(i, j), mesh.id(i + 1, j), mesh.id(i, j + 1)});
      mesh.faces.push_back({mesh.id(i + 1, j), mesh.id(i + 1, j + 1), mesh.id(i, j + 1)});
    }
  return mesh;
}

/// The lattice rolled onto a cylinder of radius 1.5 along x, with a saddle in y and in-plane
/// jitter of up to 0.1.
Lattice bent(Lattice mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (Vec3& p : mesh.points) {
    const double x = p.x() + jitter(rng), y = p.y() + jitter(rng), radius = 1.5;
    p = Vec3(radius * std::sin(x / radius), y,
             radius * (1.0 - std::cos(x / radius)) + 0.2 * (y - 2.0) * (y - 2.0));
  }
  return mesh;
}

/// A collapse patch with its local id of every lattice vertex in it.
struct LatticePatch {
  CollapsePatch patch;
  std::map<int, int> local;
};

/// The patch of collapsing lattice edge (a, b) to the midpoint raised by `lift` along z, built
/// as decimation does: the faces around a or b, then those without the edge with b renamed a.
LatticePatch collapse(const Lattice& mesh, int a, int b, double lift = 0.0) {
  LatticePatch out;
  auto local = [&](int v) {
    if (out.local.emplace(v, static_cast<int>(out.patch.points.size())).second)
      out.patch.points.push_back(mesh.points[v]);
    return out.local[v];
  };
  out.patch.a = local(a);
  out.patch.b = local(b);
  for (const Face& f : mesh.faces) {
    const bool has_a = f[0] == a || f[1] == a || f[2] == a;
    const bool has_b = f[0] == b || f[1] == b || f[2] == b;
    if (!has_a && !has_b) continue;
    const Face face{local(f[0]), local(f[1]), local(f[2])};
    out.patch.before.push_back(face);
    if (has_a && has_b) continue;
    Face merged = face;
    for (int& v : merged) v = v == out.patch.b ? out.patch.a : v;
    out.patch.after.push_back(merged);
  }
  out.patch.merged_point = 0.5 * (mesh.points[a] + mesh.points[b]) + Vec3(0.0, 0.0, lift);
  return out;
}

Vec2 corner(const CollapsePatch& patch, const JointFlattening& flat, int v, bool after) {
  return after && v == patch.a ? flat.merged_uv : flat.uv[v];
}

double area(const Vec2& p, const Vec2& q, const Vec2& r) {
  return 0.5 * ((q - p).x() * (r - p).y() - (q - p).y() * (r - p).x());
}

/// Checks every uv triangle is positive and returns the sum of their areas.
double checked_area_sum(const CollapsePatch& patch, const JointFlattening& flat, bool after) {
  double sum = 0.0;
  for (const Face& f : after ? patch.after : patch.before) {
    const double a = area(corner(patch, flat, f[0], after), corner(patch, flat, f[1], after),
                          corner(patch, flat, f[2], after));
    EXPECT_GT(a, 0.0);
    sum += a;
  }
  return sum;
}

/// Flattens with the convex map, checks positivity and equal before/after area, and that every
/// vertex but a and b (all on the loop) lies on the unit circle.
JointFlattening checked_flattening(const CollapsePatch& patch) {
  const auto flat = flatten_collapse(patch, FlatteningKind::convex);
  EXPECT_TRUE(flat.has_value());
  if (!flat) return {};
  EXPECT_NEAR(checked_area_sum(patch, *flat, false), checked_area_sum(patch, *flat, true), 1e-12);
  for (int v = 0; v < static_cast<int>(patch.points.size()); ++v)
    if (v != patch.a && v != patch.b) {
      EXPECT_NEAR(flat->uv[v].norm(), 1.0, 1e-12);
    }
  return *flat;
}

/// The lattice patches every valid-case test runs on.
std::vector<LatticePatch> valid_cases() {
  const Lattice flat = lattice(7, 6), curved = bent(flat, 7);
  std::vector<LatticePatch> cases;
  for (const Lattice* mesh : {&flat, &curved}) {
    const double lift = mesh == &flat ? 0.0 : 0.15;
    cases.push_back(collapse(*mesh, mesh->id(3, 2), mesh->id(4, 2), lift));  // interior edge
    cases.push_back(collapse(*mesh, mesh->id(3, 1), mesh->id(3, 0), lift));  // b on the border
    cases.push_back(collapse(*mesh, mesh->id(3, 0), mesh->id(3, 1), lift));  // a on the border
    cases.push_back(collapse(*mesh, mesh->id(2, 0), mesh->id(3, 0), lift));  // border edge
  }
  return cases;
}

TEST(JointFlattening, InteriorLatticeEdgeGivesRegularOctagonSymmetricAboutTheEdge) {
  const Lattice mesh = lattice(7, 6);
  const auto [patch, local] = collapse(mesh, mesh.id(3, 2), mesh.id(4, 2));
  ASSERT_EQ(patch.points.size(), 10u);  // a, b and a link of 8 unit edges
  ASSERT_EQ(patch.before.size(), 10u);
  const JointFlattening flat = checked_flattening(patch);
  // Equal arcs: a regular octagon inscribed in the unit circle, area 2√2.
  EXPECT_NEAR(checked_area_sum(patch, flat, false), 2.0 * std::sqrt(2.0), 1e-12);
  // The lattice is symmetric under a half turn about the edge midpoint, so is the flattening.
  EXPECT_NEAR((flat.uv[patch.a] + flat.uv[patch.b]).norm(), 0.0, 1e-12);
  EXPECT_NEAR(flat.merged_uv.norm(), 0.0, 1e-12);
  EXPECT_GT(flat.uv[patch.a].norm(), 0.05);
}

TEST(JointFlattening, PlanarPatchWithRegularLinkIsReproducedIsometrically) {
  // A planar octagon on the unit circle around an off-centre edge: the circle placement is then
  // a rotation of the rest shape, and mean-value weights reproduce linear maps (Floater 2003),
  // so every uv, the merged one included, keeps its distances to the loop vertices.
  CollapsePatch patch;
  patch.a = 0;
  patch.b = 1;
  patch.points = {Vec3(-0.3, 0.05, 0.0), Vec3(0.35, -0.1, 0.0)};
  for (int k = 0; k < 8; ++k)
    patch.points.emplace_back(std::cos(kPi * k / 4.0), std::sin(kPi * k / 4.0), 0.0);
  auto loop = [](int k) { return 2 + k % 8; };
  for (int k = 2; k < 6; ++k) patch.before.push_back({patch.a, loop(k), loop(k + 1)});
  for (int k = 6; k < 10; ++k) patch.before.push_back({patch.b, loop(k), loop(k + 1)});
  patch.before.push_back({patch.a, patch.b, loop(2)});
  patch.before.push_back({patch.b, patch.a, loop(6)});
  for (int k = 0; k < 8; ++k) patch.after.push_back({patch.a, loop(k), loop(k + 1)});
  patch.merged_point = Vec3(0.02, 0.03, 0.0);
  const JointFlattening flat = checked_flattening(patch);
  for (int k = 0; k < 8; ++k) {
    const Vec3& x = patch.points[loop(k)];
    const Vec2& uv = flat.uv[loop(k)];
    EXPECT_NEAR((flat.uv[patch.a] - uv).norm(), (patch.points[patch.a] - x).norm(), 1e-12);
    EXPECT_NEAR((flat.uv[patch.b] - uv).norm(), (patch.points[patch.b] - x).norm(), 1e-12);
    EXPECT_NEAR((flat.merged_uv - uv).norm(), (patch.merged_point - x).norm(), 1e-12);
  }
}

TEST(JointFlattening, ValidCollapsesFlattenOntoOnePolygon) {
  for (const auto& [patch, local] : valid_cases()) {
    checked_flattening(patch);
    const auto flat = flatten_collapse(patch);  // projected where it is valid
    ASSERT_TRUE(flat.has_value());
    EXPECT_NEAR(checked_area_sum(patch, *flat, false), checked_area_sum(patch, *flat, true), 1e-12);
  }
}

// On a planar patch the projected flattening is an isometry: every uv distance equals the 3D
// distance, the merged vertex's included, so decimating a flat sheet tracks points exactly.
TEST(JointFlattening, PlanarPatchesAreProjectedIsometrically) {
  const Lattice mesh = lattice(7, 6);
  for (const auto& [a, b] :
       {std::pair{mesh.id(3, 2), mesh.id(4, 2)}, std::pair{mesh.id(3, 1), mesh.id(3, 0)}}) {
    auto [patch, local] = collapse(mesh, a, b);
    patch.merged_point = 0.3 * patch.points[patch.a] + 0.7 * patch.points[patch.b];
    const auto flat = flatten_collapse(patch);
    ASSERT_TRUE(flat.has_value());
    EXPECT_EQ(flat->kind, FlatteningKind::projected);
    const bool interior = b == mesh.id(4, 2);
    for (std::size_t i = 0; i < patch.points.size(); ++i) {
      for (std::size_t j = 0; j < patch.points.size(); ++j)
        EXPECT_NEAR((flat->uv[i] - flat->uv[j]).norm(), (patch.points[i] - patch.points[j]).norm(),
                    1e-12);
      if (interior)
        EXPECT_NEAR((flat->merged_uv - flat->uv[i]).norm(),
                    (patch.merged_point - patch.points[i]).norm(), 1e-12);
    }
  }
}

TEST(JointFlattening, MergedVertexOnTheBorderKeepsItsBorderPosition) {
  const Lattice mesh = lattice(7, 6);
  for (const auto& [a, b] :
       {std::pair{mesh.id(3, 1), mesh.id(3, 0)}, std::pair{mesh.id(3, 0), mesh.id(3, 1)}}) {
    const auto [patch, local] = collapse(mesh, a, b);
    const JointFlattening flat = checked_flattening(patch);
    const int border = b == mesh.id(3, 0) ? patch.b : patch.a;
    EXPECT_NEAR(flat.uv[border].norm(), 1.0, 1e-12);
    EXPECT_EQ(flat.merged_uv, flat.uv[border]);
  }
}

TEST(JointFlattening, BorderEdgePutsTheRemovedVertexOnTheChord) {
  const Lattice mesh = lattice(7, 6);
  const auto [patch, local] = collapse(mesh, mesh.id(2, 0), mesh.id(3, 0));
  const JointFlattening flat = checked_flattening(patch);
  EXPECT_EQ(flat.merged_uv, flat.uv[patch.a]);
  // b is halfway along its two unit border edges: the chord midpoint.
  const Vec2 chord_mid = 0.5 * (flat.uv[patch.a] + flat.uv[local.at(mesh.id(4, 0))]);
  EXPECT_NEAR((flat.uv[patch.b] - chord_mid).norm(), 0.0, 1e-12);
  EXPECT_LT(flat.uv[patch.b].norm(), 1.0 - 1e-3);
}

TEST(JointFlattening, BorderEdgeChordParameterIsTheLengthRatio) {
  Lattice mesh = lattice(7, 6);
  mesh.points[mesh.id(3, 0)].x() += 0.3;  // |ab| = 1.3, |bq| = 0.7
  const auto [patch, local] = collapse(mesh, mesh.id(2, 0), mesh.id(3, 0));
  const JointFlattening flat = checked_flattening(patch);
  const Vec2 q = flat.uv[local.at(mesh.id(4, 0))];
  const Vec2 expected = flat.uv[patch.a] + 0.65 * (q - flat.uv[patch.a]);
  EXPECT_NEAR((flat.uv[patch.b] - expected).norm(), 0.0, 1e-12);
}

TEST(JointFlattening, NonDiskPatchesHaveNoFlattening) {
  const Lattice mesh = lattice(7, 6);
  // Two disjoint fans: two boundary loops.
  LatticePatch fans = collapse(mesh, mesh.id(1, 1), mesh.id(5, 4));
  EXPECT_FALSE(flatten_collapse(fans.patch).has_value());
  // An annulus: the interior edge's patch without the two faces on the edge.
  LatticePatch annulus = collapse(mesh, mesh.id(3, 2), mesh.id(4, 2));
  CollapsePatch& p = annulus.patch;
  p.before.erase(std::remove_if(p.before.begin(), p.before.end(),
                                [&](const Face& f) {
                                  return std::count(f.begin(), f.end(), p.a) +
                                             std::count(f.begin(), f.end(), p.b) ==
                                         2;
                                }),
                 p.before.end());
  ASSERT_EQ(p.before.size(), 8u);
  EXPECT_FALSE(flatten_collapse(p).has_value());
}

TEST(JointFlattening, InvalidCollapsesHaveNoFlattening) {
  const Lattice mesh = lattice(7, 6);
  // One face flipped: inconsistent orientation.
  LatticePatch flipped = collapse(mesh, mesh.id(3, 2), mesh.id(4, 2));
  std::swap(flipped.patch.before[3][0], flipped.patch.before[3][1]);
  EXPECT_FALSE(flatten_collapse(flipped.patch).has_value());
  // Both ends on the border but the edge interior: the collapse pinches off the corner.
  EXPECT_FALSE(flatten_collapse(collapse(mesh, mesh.id(1, 0), mesh.id(0, 1)).patch).has_value());
  // A corner ear (b of valence 2): its face lies flat on the chord, so the convex map has no
  // flattening; the projected one cuts the ear off.
  const CollapsePatch ear = collapse(mesh, mesh.id(1, 0), mesh.id(0, 0)).patch;
  EXPECT_FALSE(flatten_collapse(ear, FlatteningKind::convex).has_value());
  const auto cut = flatten_collapse(ear);
  ASSERT_TRUE(cut.has_value());
  EXPECT_EQ(cut->kind, FlatteningKind::projected);
  // A point inside the ear face lands on the new border side, with no weight on the far
  // corner of its after face.
  int ear_face = -1;
  for (std::size_t f = 0; f < ear.before.size(); ++f)
    if (std::count(ear.before[f].begin(), ear.before[f].end(), ear.b))
      ear_face = static_cast<int>(f);
  ASSERT_GE(ear_face, 0);
  const auto [after_face, weights] = relocate_point(ear, *cut, ear_face, Vec3(0.2, 0.3, 0.5));
  EXPECT_NEAR(weights.minCoeff(), 0.0, 1e-12);
  EXPECT_NEAR(weights.sum(), 1.0, 1e-12);
}

TEST(JointFlattening, BadIdsThrow) {
  const Lattice mesh = lattice(7, 6);
  LatticePatch lp = collapse(mesh, mesh.id(3, 2), mesh.id(4, 2));
  const JointFlattening flat = checked_flattening(lp.patch);
  EXPECT_THROW(
      relocate_point(lp.patch, flat, static_cast<int>(lp.patch.before.size()), Vec3(1, 0, 0)),
      Error);
  lp.patch.after[0][1] = static_cast<int>(lp.patch.points.size());
  EXPECT_THROW(flatten_collapse(lp.patch), Error);
}

TEST(JointFlattening, RelocatedPointsKeepTheirUv) {
  std::mt19937 rng(3);
  std::exponential_distribution<double> spread(1.0);
  for (const auto& [patch, local] : valid_cases()) {
    const JointFlattening flat = checked_flattening(patch);
    std::uniform_int_distribution<int> face(0, static_cast<int>(patch.before.size()) - 1);
    for (int trial = 0; trial < 1000; ++trial) {
      const int f = face(rng);
      Vec3 w(spread(rng), spread(rng), spread(rng));
      if (trial % 3 == 0) w[trial % 9 / 3] = 0.0;  // on an edge of the before face
      w /= w.sum();
      Vec2 uv = Vec2::Zero();
      for (int k = 0; k < 3; ++k) uv += w[k] * flat.uv[patch.before[f][k]];
      const auto [j, weights] = relocate_point(patch, flat, f, w);
      ASSERT_GE(j, 0);
      ASSERT_LT(j, static_cast<int>(patch.after.size()));
      Vec2 back = Vec2::Zero();
      for (int k = 0; k < 3; ++k) back += weights[k] * corner(patch, flat, patch.after[j][k], true);
      EXPECT_NEAR((back - uv).norm(), 0.0, 1e-12);
      EXPECT_GE(weights.minCoeff(), 0.0);
      EXPECT_NEAR(weights.sum(), 1.0, 1e-14);
    }
  }
}

TEST(JointFlattening, PointsAtLoopVerticesStayThere) {
  for (const auto& [patch, local] : valid_cases()) {
    const JointFlattening flat = checked_flattening(patch);
    auto on_circle = [&](int v) { return std::abs(flat.uv[v].norm() - 1.0) < 1e-12; };
    for (int f = 0; f < static_cast<int>(patch.before.size()); ++f)
      for (int k = 0; k < 3; ++k) {
        const int v = patch.before[f][k];
        // Every vertex but a and b is on the loop; a or b on the loop ends at the merged a.
        if ((v == patch.a || v == patch.b) && !on_circle(v)) continue;
        const int expected = v == patch.b ? patch.a : v;
        const auto [j, weights] = relocate_point(patch, flat, f, Vec3::Unit(k));
        const Face& after = patch.after[j];
        const auto at = std::find(after.begin(), after.end(), expected);
        ASSERT_NE(at, after.end());
        EXPECT_NEAR(weights[at - after.begin()], 1.0, 1e-12);
      }
  }
}

}  // namespace
