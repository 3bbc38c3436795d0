// A tet hierarchy built by decimating the boundary and tetrahedralizing each level (VPD §3.1.2):
// valid levels, shrinking vertex counts, prolongations that reproduce affine maps with bounded
// weights, level volumes close to the finest, progress and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "hierarchy/tet_hierarchy.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/tet_generators.hpp"
#include "mesh/tet_mesh_validation.hpp"
#include "mesh/tetrahedralize.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using progsim::test_support::expect_error;

namespace {

/// A ball of radius 0.5 m tetrahedralized from a 642-vertex icosphere.
TetMesh tet_ball() {
  TetrahedralizeOptions options;
  options.cell_size = 0.05;
  return tetrahedralize_surface(make_sphere(0.5, 3), options);
}

/// An affine map x ↦ A x + b with a shear, a stretch and a rotation, applied to every row.
Positions affine(const Positions& x) {
  Mat3 a;
  a << 1.2, 0.3, -0.1, -0.2, 0.9, 0.4, 0.05, -0.3, 1.1;
  const Vec3 b(0.7, -1.3, 2.1);
  Positions out = x * a.transpose();
  out.rowwise() += b.transpose();
  return out;
}

/// Checks every level and prolongation of `h` (level volumes within volume_tolerance relative
/// of the finest, weights within [min_weight, max_weight]) and prints what the report needs.
void check_hierarchy_levels(const TetHierarchy& h, double volume_tolerance, double min_weight,
                            double max_weight) {
  const TetMesh& finest = h.levels.back();
  const double finest_volume = tet_mesh_volume(finest);
  for (int l = 0; l < h.num_levels(); ++l) {
    validate_tet_mesh(h.levels[l], "level " + std::to_string(l));
    const double volume = tet_mesh_volume(h.levels[l]);
    std::printf("level %d: %d vertices, %d tets, volume %.6g (%.3g %% from the finest)\n", l,
                h.levels[l].num_vertices(), h.levels[l].num_tets(), volume,
                100.0 * (volume / finest_volume - 1.0));
    EXPECT_NEAR(volume, finest_volume, volume_tolerance * finest_volume) << "level " << l;
    if (l > 0) EXPECT_LT(h.levels[l - 1].num_vertices(), h.levels[l].num_vertices());
  }
  for (int l = 0; l + 1 < h.num_levels(); ++l) {
    const ProlongationMatrix& w = h.to_finer[l];
    const TetMesh &coarse = h.levels[l], &fine = h.levels[l + 1];
    ASSERT_EQ(w.rows(), fine.num_vertices());
    ASSERT_EQ(w.cols(), coarse.num_vertices());
    const double scale = bounding_box_diagonal(fine.vertices);
    EXPECT_LE((w * coarse.vertices - fine.vertices).cwiseAbs().maxCoeff(), 1e-10 * scale);
    EXPECT_LE((w * affine(coarse.vertices) - affine(fine.vertices)).cwiseAbs().maxCoeff(),
              1e-10 * scale);
    const Eigen::VectorXd row_sums = w * Eigen::VectorXd::Ones(w.cols());
    EXPECT_LE((row_sums.array() - 1.0).abs().maxCoeff(), 1e-12);
    double largest = 0.0, smallest = 0.0;
    int negative = 0;
    for (int k = 0; k < w.outerSize(); ++k)
      for (ProlongationMatrix::InnerIterator it(w, k); it; ++it) {
        largest = std::max(largest, std::abs(it.value()));
        smallest = std::min(smallest, it.value());
        negative += it.value() < 0.0;
      }
    std::printf("W_%d (%d x %d): max |w| %.3f, %.2f %% of %d entries negative\n", l,
                static_cast<int>(w.rows()), static_cast<int>(w.cols()), largest,
                100.0 * negative / w.nonZeros(), static_cast<int>(w.nonZeros()));
    EXPECT_LE(largest, max_weight);
    EXPECT_GE(smallest, min_weight);
  }
}

/// Records the fractions a build reports; cancels after `stop_after` calls (never if < 0).
struct ProgressLog {
  std::vector<double> fractions;
  int stop_after = -1;
  static bool record(void* user, double fraction, const char*) {
    auto* log = static_cast<ProgressLog*>(user);
    log->fractions.push_back(fraction);
    return log->stop_after < 0 || static_cast<int>(log->fractions.size()) < log->stop_after;
  }
};

}  // namespace

TEST(TetHierarchy, BallLevelsAreValidShrinkAndProlongAffineMapsExactly) {
  const TetMesh finest = tet_ball();
  TetHierarchyOptions options;
  options.coarse_boundary_vertex_counts = {300, 100, 40};
  ProgressLog log;
  const TetHierarchy h = build_tet_hierarchy(finest, options, &ProgressLog::record, &log);
  ASSERT_EQ(h.num_levels(), 4);
  EXPECT_TRUE(h.levels.back().vertices == finest.vertices);
  EXPECT_TRUE(h.levels.back().tets == finest.tets);
  // Decimation by quadric optima and a tetrahedralization inscribed in each S_l shrink the
  // coarse balls: 10 % at 40 boundary vertices (measured 9.4 %).
  check_hierarchy_levels(h, 0.1, -3.0, 3.0);
  const double ball = 4.0 / 3.0 * M_PI * 0.125;
  std::printf("finest volume %.3g %% from the ball's\n",
              100.0 * (tet_mesh_volume(finest) / ball - 1.0));
  ASSERT_FALSE(log.fractions.empty());
  for (std::size_t k = 1; k < log.fractions.size(); ++k)
    EXPECT_GE(log.fractions[k], log.fractions[k - 1]);
  EXPECT_DOUBLE_EQ(log.fractions.back(), 1.0);
}

TEST(TetHierarchy, BoxLevelsKeepingInputPositionsAreTheSameBoxWithoutExtrapolation) {
  // Every decimated vertex keeps an input position, so S_l lies on the box's planes with its
  // corners, Mesh_3 protects the sharp edges, and each level fills the box exactly, so every
  // weight lies in [0, 1] (Mesh_3's sliver perturbation leaves boundary vertices up to 1 ulp
  // off the planes; bind_to_tets counts those as inside: it once gave one of them −0.218).
  const TetMesh finest = make_tet_box(Vec3(1.0, 0.6, 0.4), 10, 6, 4);
  TetHierarchyOptions options;
  options.coarse_boundary_vertex_counts = {120, 40};
  options.keep_input_positions = true;
  const TetHierarchy h = build_tet_hierarchy(finest, options);
  ASSERT_EQ(h.num_levels(), 3);
  check_hierarchy_levels(h, 1e-9, -1e-9, 1.0 + 1e-9);
  for (const TetMesh& level : h.levels) EXPECT_NEAR(tet_mesh_volume(level), 0.24, 0.24e-9);
}

TEST(TetHierarchy, TwoBuildsAreIdentical) {
  const TetMesh finest = make_tet_box(Vec3(1.0, 0.6, 0.4), 10, 6, 4);
  TetHierarchyOptions options;
  options.coarse_boundary_vertex_counts = {100, 30};
  const TetHierarchy a = build_tet_hierarchy(finest, options);
  const TetHierarchy b = build_tet_hierarchy(finest, options);
  ASSERT_EQ(a.num_levels(), b.num_levels());
  for (int l = 0; l < a.num_levels(); ++l) {
    ASSERT_EQ(a.levels[l].num_tets(), b.levels[l].num_tets());
    EXPECT_TRUE(a.levels[l].vertices == b.levels[l].vertices);
    EXPECT_TRUE(a.levels[l].tets == b.levels[l].tets);
  }
}

TEST(TetHierarchy, NoCountsGiveTheInputAlone) {
  const TetMesh finest = make_tet_box(Vec3(1.0, 1.0, 1.0), 2, 2, 2);
  const TetHierarchy h = build_tet_hierarchy(finest, {});
  ASSERT_EQ(h.num_levels(), 1);
  EXPECT_TRUE(h.to_finer.empty());
  EXPECT_TRUE(h.levels[0].tets == finest.tets);
}

TEST(TetHierarchy, RejectsBadCountsAndSizes) {
  const TetMesh finest = make_tet_box(Vec3(1.0, 1.0, 1.0), 3, 3, 3);  // 56 boundary vertices
  TetHierarchyOptions options;
  for (const std::vector<int>& counts :
       std::vector<std::vector<int>>{{3}, {56}, {20, 20}, {-1, 10}}) {
    options.coarse_boundary_vertex_counts = counts;
    expect_error([&] { build_tet_hierarchy(finest, options); }, Status::invalid_argument,
                 {"tet hierarchy", "boundary vertex count", "56"});
  }
  options.coarse_boundary_vertex_counts = {20};
  options.size_factor = 0.0;
  expect_error([&] { build_tet_hierarchy(finest, options); }, Status::invalid_argument,
               {"size_factor"});
}

TEST(TetHierarchy, RejectsAnInvalidFinestMesh) {
  TetMesh finest = make_tet_box(Vec3(1.0, 1.0, 1.0), 2, 2, 2);
  std::swap(finest.tets(0, 0), finest.tets(0, 1));  // inverted
  expect_error([&] { build_tet_hierarchy(finest, {}); }, Status::invalid_mesh,
               {"finest level", "tet 0"});
}

TEST(TetHierarchy, ProgressCanCancel) {
  const TetMesh finest = make_tet_box(Vec3(1.0, 0.6, 0.4), 10, 6, 4);
  TetHierarchyOptions options;
  options.coarse_boundary_vertex_counts = {100, 30};
  for (int stop_after : {1, 4}) {  // during decimation; after the first tetrahedralization
    ProgressLog log;
    log.stop_after = stop_after;
    expect_error([&] { build_tet_hierarchy(finest, options, &ProgressLog::record, &log); },
                 Status::cancelled, {"cancelled"});
  }
}
