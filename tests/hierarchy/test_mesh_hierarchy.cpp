// Mesh hierarchies built by decimation (PSQ §4.1–4.4) on a flat sheet, a curved dome, a closed
// sphere, a real mesh with holes and boundary and an irregular real mesh: level sizes and
// validity, topology kept, exact rest recovery by the shell prolongations (PSQ eqs. 7 and 9),
// rigid-motion equivariance, smooth prolongation of a bent sheet, sparsity, expansion batches
// (independent, replaying to the finer level), save/load, progress, cancellation, bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <set>

#include "hierarchy/expansion_coloring.hpp"
#include "hierarchy/hierarchy_io.hpp"
#include "hierarchy/hierarchy_test_meshes.hpp"
#include "hierarchy/level_prolongation.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_test_support.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh/mesh_validation.hpp"
#include "support/energy_checks.hpp"
#include "support/real_meshes.hpp"

using namespace progsim;
using namespace progsim::test_support;
namespace fs = std::filesystem;

namespace {

/// A grid with random diagonals, in-plane jitter and a random height field: irregular.
TriangleMesh irregular_sheet() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const int n = 28;
  TriangleMesh mesh;
  mesh.vertices.resize((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool inner = i > 0 && j > 0 && i < n && j < n;
      const double x = (i + (inner ? jitter(rng) : 0.0)) / n;
      const double y = (j + (inner ? jitter(rng) : 0.0)) / n;
      mesh.vertices.row(j * (n + 1) + i) << x, y, 0.05 * std::sin(7 * x) * std::cos(5 * y);
    }
  mesh.faces.resize(2 * n * n, 3);
  for (int j = 0, f = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      if (rng() % 2) {
        mesh.faces.row(f++) << a, b, d;
        mesh.faces.row(f++) << a, d, c;
      } else {
        mesh.faces.row(f++) << a, b, c;
        mesh.faces.row(f++) << b, d, c;
      }
    }
  return mesh;
}

struct HierarchyCase {
  std::string name;
  TriangleMesh mesh;
  std::vector<int> counts;
};

std::vector<HierarchyCase> cases() {
  return {{"flat sheet", make_grid(1.0, 1.0, 30, 30), {60, 240}},
          {"dome", dome(24), {50, 200}},
          {"closed sphere", make_sphere(1.0, 3), {42, 160}},
          {"elephant with holes", real_mesh("elephant-with-holes.off"), {500, 1200}},
          {"irregular sheet", irregular_sheet(), {50, 200}},
          {"cow (irregular, closed)", real_mesh("cow.off"), {180, 720}}};
}

/// Euler characteristic V − E + F and number of boundary edges.
std::array<int, 2> euler_and_boundary(const TriangleMesh& mesh) {
  const MeshTopology topology = build_topology(mesh.faces, mesh.num_vertices());
  const int boundary = static_cast<int>(
      std::count(topology.edge_on_boundary.begin(), topology.edge_on_boundary.end(), true));
  return {mesh.num_vertices() - static_cast<int>(topology.edges.size()) + mesh.num_faces(),
          boundary > 0};
}

/// Largest angle between the normals of two faces sharing an edge (radians).
double max_dihedral_angle(const Positions& x, const Faces& faces) {
  const MeshTopology topology = build_topology(faces, static_cast<int>(x.rows()));
  auto normal = [&](int f) {
    const Vec3 p0 = x.row(faces(f, 0)), p1 = x.row(faces(f, 1)), p2 = x.row(faces(f, 2));
    return Vec3((p1 - p0).cross(p2 - p0).normalized());
  };
  double worst = 0.0;
  for (const Hinge& h : topology.hinges)
    worst = std::max(worst, std::acos(std::clamp(normal(h.f0).dot(normal(h.f1)), -1.0, 1.0)));
  return worst;
}

/// Faces as a sorted list of rotation-normalised triples (smallest id first, order kept).
std::vector<FaceCorners> canonical(std::vector<FaceCorners> faces) {
  for (auto& f : faces) std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
  std::sort(faces.begin(), faces.end());
  return faces;
}

class EveryMesh : public ::testing::TestWithParam<int> {
 protected:
  static void SetUpTestSuite() {
    for (const HierarchyCase& c : cases()) {
      HierarchyOptions options;
      options.coarse_vertex_counts = c.counts;
      built_.push_back(build_hierarchy(c.mesh, options));
      names_.push_back(c.name);
    }
  }
  static void TearDownTestSuite() { built_.clear(); }
  const MeshHierarchy& hierarchy() const { return built_[GetParam()]; }
  const std::string& name() const { return names_[GetParam()]; }
  static inline std::vector<MeshHierarchy> built_;
  static inline std::vector<std::string> names_;
};

TEST_P(EveryMesh, LevelsHaveTheAskedSizesAreValidAndKeepTheTopology) {
  const MeshHierarchy& h = hierarchy();
  const HierarchyCase c = cases()[GetParam()];
  ASSERT_EQ(h.num_levels(), static_cast<int>(c.counts.size()) + 1) << name();
  const auto finest = euler_and_boundary(c.mesh);
  for (int l = 0; l < h.num_levels(); ++l) {
    const TriangleMesh& rest = h.levels[l].rest;
    if (l < h.finest()) EXPECT_EQ(rest.num_vertices(), c.counts[l]) << name();
    EXPECT_NO_THROW(validate_mesh(rest, "level")) << name() << " level " << l;
    EXPECT_EQ(euler_and_boundary(rest), finest) << name() << " level " << l;
    for (int v = 0; v < rest.num_vertices(); ++v)
      ASSERT_EQ(h.levels[l].input_vertex[v] < c.mesh.num_vertices(), true);
  }
  EXPECT_EQ(h.levels.back().rest.vertices, c.mesh.vertices);
}

TEST_P(EveryMesh, ShellProlongationRecoversTheRestShapeExactly) {
  const MeshHierarchy& h = hierarchy();
  const Positions& finest = h.levels.back().rest.vertices;
  const double tolerance = 1e-9 * bounding_box_diagonal(finest);
  for (int l = 0; l < h.finest(); ++l) {
    const Positions& coarse = h.levels[l].rest.vertices;
    EXPECT_LT(max_row_distance(direct_prolongation(h, l)(coarse), finest), tolerance)
        << name() << " P^" << l;
    EXPECT_LT(
        max_row_distance(next_level_prolongation(h, l)(coarse), h.levels[l + 1].rest.vertices),
        tolerance)
        << name() << " P^" << l << "_" << l + 1;
  }
}

TEST_P(EveryMesh, IntrinsicMapIsSparseAndPutsFineVerticesNearTheirPlace) {
  const MeshHierarchy& h = hierarchy();
  const Positions& finest = h.levels.back().rest.vertices;
  for (int l = 0; l < h.finest(); ++l) {
    const ShellProlongation p = direct_prolongation(h, l);
    EXPECT_LE(p.intrinsic().nonZeros(), 3 * finest.rows());
    const Vector ones = Vector::Ones(p.intrinsic().cols());
    EXPECT_LT((p.intrinsic() * ones - Vector::Ones(p.intrinsic().rows())).cwiseAbs().maxCoeff(),
              1e-9);
    // U x̄_l lies on the coarse surface: within a few coarse edge lengths of x̄_L, never across
    // the mesh (a wrong anchor would be).
    const TriangleMesh& coarse = h.levels[l].rest;
    double longest_edge = 0.0;
    for (int f = 0; f < coarse.num_faces(); ++f)
      for (int k = 0; k < 3; ++k)
        longest_edge = std::max(longest_edge, (coarse.vertices.row(coarse.faces(f, k)) -
                                               coarse.vertices.row(coarse.faces(f, (k + 1) % 3)))
                                                  .norm());
    const Positions u_part = p.intrinsic() * coarse.vertices;
    EXPECT_LT(max_row_distance(u_part, finest), 2.0 * longest_edge) << name() << " level " << l;
  }
}

TEST_P(EveryMesh, ProlongationCommutesWithRigidMotions) {
  const MeshHierarchy& h = hierarchy();
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 0.01);
  for (int l = 0; l < h.finest(); ++l) {
    const ShellProlongation p = direct_prolongation(h, l);
    Positions x = h.levels[l].rest.vertices;
    for (int i = 0; i < x.rows(); ++i)
      x.row(i) += Eigen::RowVector3d(normal(rng), normal(rng), normal(rng));
    const Positions px = p(x);
    for (int trial = 0; trial < 3; ++trial) {
      const Mat3 q = random_rotation(rng);
      const Eigen::RowVector3d c(normal(rng) * 100, normal(rng) * 100, normal(rng) * 100);
      const Positions moved = (x * q.transpose()).rowwise() + c;
      const Positions expected = (px * q.transpose()).rowwise() + c;
      EXPECT_LT(max_row_distance(p(moved), expected), 1e-9 * bounding_box_diagonal(px))
          << name() << " level " << l;
    }
  }
}

TEST_P(EveryMesh, ExpansionBatchesAreIndependentAndReplayToTheFinerLevel) {
  const MeshHierarchy& h = hierarchy();
  for (int l = 0; l < h.finest(); ++l) {
    std::vector<int> seen(h.collapses.size(), 0);
    std::vector<FaceCorners> faces = level_input_faces(h.levels[l]);
    for (const auto& batch : h.expansion_batches[l]) {
      // Closed one-rings of the kept vertices in the current mesh, with the split's own faces:
      // pairwise disjoint within a batch (PSQ Algorithm 7).
      std::map<int, int> owner;
      for (int r : batch) {
        ++seen[r];
        std::set<int> ring;
        for (const auto& f : faces)
          if (std::find(f.begin(), f.end(), h.collapses[r].kept) != f.end())
            ring.insert(f.begin(), f.end());
        for (const auto& f : h.collapses[r].before) ring.insert(f.begin(), f.end());
        for (int v : ring) {
          const auto [it, fresh] = owner.emplace(v, r);
          EXPECT_TRUE(fresh) << name() << ": splits " << it->second << " and " << r
                             << " share vertex " << v;
        }
      }
      apply_splits(faces, h.collapses, batch);
    }
    for (int r = h.first_collapse[l + 1]; r < h.first_collapse[l]; ++r) EXPECT_EQ(seen[r], 1);
    EXPECT_EQ(canonical(faces), canonical(level_input_faces(h.levels[l + 1])))
        << name() << " level " << l;
    const int splits = h.first_collapse[l] - h.first_collapse[l + 1];
    // Batches run several splits each (a wave per batch, not one split at a time).
    EXPECT_LT(h.expansion_batches[l].size(), splits / 2u) << name();
  }
}

TEST_P(EveryMesh, SavedAndLoadedHierarchyProlongsTheSame) {
  const MeshHierarchy& h = hierarchy();
  const fs::path path =
      fs::temp_directory_path() / ("progsim_hierarchy_" + std::to_string(GetParam()) + ".bin");
  save_hierarchy(h, path.string());
  const MeshHierarchy loaded = load_hierarchy(path.string());
  fs::remove(path);
  ASSERT_EQ(loaded.num_levels(), h.num_levels());
  for (int l = 0; l < h.finest(); ++l) {
    const Positions x = h.levels[l].rest.vertices * 1.1;
    EXPECT_EQ(direct_prolongation(loaded, l)(x), direct_prolongation(h, l)(x));
    EXPECT_EQ(loaded.expansion_batches[l], h.expansion_batches[l]);
  }
}

INSTANTIATE_TEST_SUITE_P(Hierarchy, EveryMesh, ::testing::Range(0, 6));

/// Mean edge length of a mesh.
double mean_edge_length(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      sum += (mesh.vertices.row(mesh.faces(f, k)) - mesh.vertices.row(mesh.faces(f, (k + 1) % 3)))
                 .norm();
  return sum / (3.0 * mesh.num_faces());
}

// A smooth bend of the coarse level prolongs without spikes: the fine mesh folds no sharper
// than the coarse one (within 10%), and it follows the same bend applied to the fine rest shape
// closely (the offsets turn with the coarse faces). Flat sheet bent around a cylinder; dome bent by
// a height field.
TEST(HierarchySmoothness, BentCoarseLevelsProlongWithoutSpikes) {
  const double radius = 0.3;
  auto cylinder = [radius](const Eigen::RowVector3d& p) {
    return Eigen::RowVector3d(radius * std::sin(p.x() / radius), p.y(),
                              p.z() + radius * (1.0 - std::cos(p.x() / radius)));
  };
  auto height = [](const Eigen::RowVector3d& p) {
    return Eigen::RowVector3d(p.x(), p.y(), p.z() + 0.8 * p.x() * p.x() - 0.3 * p.y());
  };
  struct Bend {
    TriangleMesh mesh;
    std::function<Eigen::RowVector3d(const Eigen::RowVector3d&)> map;
  };
  for (const Bend& bend : {Bend{make_grid(1.0, 1.0, 40, 40), cylinder}, Bend{dome(24), height}}) {
    HierarchyOptions options;
    options.coarse_vertex_counts = {100};
    const MeshHierarchy h = build_hierarchy(bend.mesh, options);
    const TriangleMesh& coarse = h.levels[0].rest;
    Positions bent = coarse.vertices, exact = bend.mesh.vertices;
    for (int i = 0; i < bent.rows(); ++i) bent.row(i) = bend.map(bent.row(i));
    for (int i = 0; i < exact.rows(); ++i) exact.row(i) = bend.map(exact.row(i));
    const Positions fine = direct_prolongation(h, 0)(bent);
    const double coarse_fold = max_dihedral_angle(bent, coarse.faces);
    const double fine_fold = max_dihedral_angle(fine, bend.mesh.faces);
    const double distance = max_row_distance(fine, exact);
    // Fine triangles across a coarse crease reproduce it (up to a few percent); a spike would
    // fold far sharper.
    EXPECT_LE(fine_fold, 1.1 * coarse_fold) << "fine " << fine_fold << " coarse " << coarse_fold;
    EXPECT_LT(distance, 0.25 * mean_edge_length(coarse))
        << distance << " vs coarse edge " << mean_edge_length(coarse);
    std::printf(
        "bend: coarse fold %.3f rad, fine fold %.3f rad, max distance to the bent fine "
        "rest %.4f m (coarse edge %.4f m)\n",
        coarse_fold, fine_fold, distance, mean_edge_length(coarse));
  }
}

// Vertex groups (handles) survive decimation: the bottom and top rows of a sheet and one
// interior vertex, on every level, stay where the input had them, never merge, and the
// shell prolongation still recovers the rest shape.
TEST(HierarchyGroups, HandlesKeepTheirPlaceOnEveryLevel) {
  const TriangleMesh sheet = make_grid(1.0, 1.0, 30, 30);
  HierarchyOptions options;
  options.coarse_vertex_counts = {60, 240};
  options.vertex_groups.assign(sheet.num_vertices(), -1);
  for (int i = 0; i <= 30; ++i) {
    options.vertex_groups[i] = 0;            // y = 0
    options.vertex_groups[30 * 31 + i] = 1;  // y = 1
  }
  const int centre = 15 * 31 + 15;
  options.vertex_groups[centre] = 2;
  const MeshHierarchy h = build_hierarchy(sheet, options);
  EXPECT_EQ(h.input_group, options.vertex_groups);
  for (int l = 0; l < h.num_levels(); ++l) {
    const std::vector<int> group = level_groups(h, l);
    const Positions& x = h.levels[l].rest.vertices;
    std::array<int, 3> count{0, 0, 0};
    for (int v = 0; v < x.rows(); ++v) {
      if (group[v] < 0) continue;
      ++count[group[v]];
      // A grouped vertex sits exactly where one input vertex of its group was.
      bool found = false;
      for (int i = 0; i < sheet.num_vertices() && !found; ++i)
        found = options.vertex_groups[i] == group[v] && sheet.vertices.row(i) == x.row(v);
      EXPECT_TRUE(found) << "level " << l << " vertex " << v << " of group " << group[v];
    }
    EXPECT_GE(count[0], 2) << "level " << l;  // the row's two ends at least
    EXPECT_GE(count[1], 2) << "level " << l;
    EXPECT_EQ(count[2], 1) << "level " << l;
    if (l < h.finest())
      EXPECT_LT(max_row_distance(direct_prolongation(h, l)(x), sheet.vertices),
                1e-9 * bounding_box_diagonal(sheet.vertices));
  }
  HierarchyOptions bad = options;
  bad.vertex_groups.pop_back();
  expect_error([&] { build_hierarchy(sheet, bad); }, Status::invalid_argument,
               {"960 vertex groups for 961 vertices"});
  bad = options;
  bad.vertex_groups[3] = -4;
  expect_error([&] { build_hierarchy(sheet, bad); }, Status::invalid_argument, {"vertex 3"});
}

TEST(HierarchyProgress, ReportsIncreasingFractionsAndCanCancel) {
  const TriangleMesh sheet = make_grid(1.0, 1.0, 20, 20);
  HierarchyOptions options;
  options.coarse_vertex_counts = {40, 120};
  std::vector<double> fractions;
  auto record = [](void* user, double fraction, const char*) {
    static_cast<std::vector<double>*>(user)->push_back(fraction);
    return true;
  };
  build_hierarchy(sheet, options, record, &fractions);
  ASSERT_GT(fractions.size(), 10u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  auto cancel = [](void*, double fraction, const char*) { return fraction < 0.5; };
  expect_error([&] { build_hierarchy(sheet, options, cancel, nullptr); }, Status::cancelled,
               {"cancelled"});
}

TEST(HierarchyBadInput, ClearErrors) {
  const TriangleMesh sheet = make_grid(1.0, 1.0, 4, 4);  // 25 vertices
  HierarchyOptions options;
  options.coarse_vertex_counts = {25};
  expect_error([&] { build_hierarchy(sheet, options); }, Status::invalid_argument,
               {"25", "below the mesh's 25 vertices"});
  options.coarse_vertex_counts = {3};
  expect_error([&] { build_hierarchy(sheet, options); }, Status::invalid_argument, {"at least 4"});
  options.coarse_vertex_counts = {10, 10};
  expect_error([&] { build_hierarchy(sheet, options); }, Status::invalid_argument, {"distinct"});
  options.coarse_vertex_counts = {10};
  expect_error(
      [&] { build_hierarchy(read_mesh(PROGSIM_TEST_DATA_DIR "/non_manifold.off"), options); },
      Status::invalid_mesh, {});
  TriangleMesh degenerate = sheet;
  degenerate.vertices.row(6) = degenerate.vertices.row(7);
  expect_error([&] { build_hierarchy(degenerate, options); }, Status::invalid_mesh, {});
  TriangleMesh with_nan = sheet;
  with_nan.vertices(3, 1) = std::nan("");
  expect_error([&] { build_hierarchy(with_nan, options); }, Status::invalid_mesh, {});
}

// Half of elephant-with-holes' vertices lie on its hole borders; below about 330 vertices every
// vertex is a border vertex and no collapse keeps the surface valid (plain CGAL stops there
// too): the error says where decimation stopped.
TEST(HierarchyBadInput, TooCoarseForTheSurfaceIsReported) {
  HierarchyOptions options;
  options.coarse_vertex_counts = {150};
  expect_error([&] { build_hierarchy(real_mesh("elephant-with-holes.off"), options); },
               Status::invalid_mesh, {"level 0 (150 vertices asked for)", "stopped at"});
}

}  // namespace
