// Hierarchy files: exact round trips of a hand-made two-level hierarchy, check_hierarchy
// catching each kind of inconsistency, and load_hierarchy rejecting missing, truncated and
// corrupt files with an Error (never a crash or a huge allocation).
#include <gtest/gtest.h>
#include <unistd.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>

#include "common/error.hpp"
#include "hierarchy/hierarchy_io.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/mesh_generators.hpp"
#include "mesh/mesh_test_support.hpp"

using namespace progsim;
using namespace progsim::test_support;
namespace fs = std::filesystem;

namespace {

/// Byte offsets in a version-1 file: magic (6), version (4), marker (4), level count (8), then
/// level 0's vertex count.
constexpr std::size_t kVersionOffset = 6;
constexpr std::size_t kLevelCountOffset = 14;
constexpr std::size_t kFirstVertexCountOffset = 22;

/// Anchor of the point (x, y) of the unit square on level 0's faces (0,0)-(1,0)-(1,1) and
/// (0,0)-(1,1)-(0,1). Points on the diagonal go to face 0 if `diagonal_on_face_0`.
SurfaceAnchor square_anchor(double x, double y, bool diagonal_on_face_0) {
  if (x > y || (x == y && diagonal_on_face_0)) return {0, Vec3(1 - x, x - y, y)};
  return {1, Vec3(1 - y, x, y - x)};
}

SurfaceAnchors anchors_of(const TriangleMesh& fine, bool diagonal_on_face_0) {
  SurfaceAnchors anchors;
  for (int v = 0; v < fine.num_vertices(); ++v)
    anchors.push_back(square_anchor(fine.vertices(v, 0), fine.vertices(v, 1), diagonal_on_face_0));
  return anchors;
}

/// Level 1: the 3 × 3 grid, lifted a little off the plane so that the coordinates need all
/// their bits. Level 0: its four corners (input ids 0, 2, 6, 8) as two triangles.
std::vector<HierarchyLevel> square_levels() {
  TriangleMesh grid = make_grid(1.0, 1.0, 2, 2);
  for (int v = 0; v < grid.num_vertices(); ++v)
    grid.vertices(v, 2) = 1e-3 * std::sin(17.0 * v + 0.1);
  HierarchyLevel fine{grid, {0, 1, 2, 3, 4, 5, 6, 7, 8}};
  HierarchyLevel coarse;
  coarse.input_vertex = {0, 2, 6, 8};
  coarse.rest.vertices.resize(4, 3);
  for (int i = 0; i < 4; ++i)
    coarse.rest.vertices.row(i) = grid.vertices.row(coarse.input_vertex[i]);
  coarse.rest.faces.resize(2, 3);
  coarse.rest.faces << 0, 1, 3, 0, 3, 2;
  return {coarse, fine};
}

/// Collapses removing the grid's edge midpoints and centre (ids in the input numbering).
std::vector<CollapseRecord> square_collapses() {
  return {
      {1, 0, {{0, 1, 4}, {0, 4, 3}, {1, 2, 4}}, {{0, 2, 4}, {0, 4, 3}}},
      {3, 0, {{0, 2, 4}, {0, 4, 3}, {3, 4, 6}}, {{0, 2, 4}, {0, 4, 6}}},
      {5, 2, {{0, 2, 4}, {2, 5, 4}, {4, 5, 8}}, {{0, 2, 4}, {2, 8, 4}}},
      {7, 6, {{4, 7, 6}, {4, 8, 7}, {0, 4, 6}}, {{4, 8, 6}, {0, 4, 6}}},
      {4, 0, {{0, 2, 4}, {2, 8, 4}, {4, 8, 6}, {0, 4, 6}}, {{0, 2, 8}, {0, 8, 6}}},
  };
}

/// A valid two-level hierarchy built by hand. to_next and to_finest differ (on the diagonal)
/// so that a round trip swapping them would show.
MeshHierarchy square_hierarchy() {
  MeshHierarchy h;
  h.levels = square_levels();
  h.to_next = {anchors_of(h.levels[1].rest, true)};
  h.to_finest = {anchors_of(h.levels[1].rest, false)};
  h.collapses = square_collapses();
  h.first_collapse = {5, 0};
  h.expansion_batches = {{{0, 1, 2}, {3, 4}}};
  h.input_group = {0, -1, -1, -1, 1, -1, -1, -1, -1};
  return h;
}

/// A decimated 7 × 7 grid: levels of 12, 25 and 49 vertices (real records and batches, which
/// load_hierarchy replays).
MeshHierarchy built_hierarchy() {
  HierarchyOptions options;
  options.coarse_vertex_counts = {12, 25};
  options.vertex_groups.assign(49, -1);
  for (int i = 0; i < 7; ++i) options.vertex_groups[i] = 0;  // the bottom row, one handle
  return build_hierarchy(make_grid(1.0, 1.0, 6, 6), options);
}

/// The user's mesh alone.
MeshHierarchy single_level_hierarchy() {
  MeshHierarchy h;
  h.levels = {square_levels()[1]};
  h.first_collapse = {0};
  h.input_group.assign(9, -1);
  return h;
}

void expect_same_anchors(const std::vector<SurfaceAnchors>& a,
                         const std::vector<SurfaceAnchors>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t l = 0; l < a.size(); ++l) {
    ASSERT_EQ(a[l].size(), b[l].size());
    for (std::size_t i = 0; i < a[l].size(); ++i) {
      EXPECT_EQ(a[l][i].face, b[l][i].face) << "list " << l << " anchor " << i;
      EXPECT_EQ(a[l][i].weights, b[l][i].weights) << "list " << l << " anchor " << i;
    }
  }
}

/// Every field equal, doubles bit for bit.
void expect_same_hierarchy(const MeshHierarchy& a, const MeshHierarchy& b) {
  ASSERT_EQ(a.num_levels(), b.num_levels());
  for (int l = 0; l < a.num_levels(); ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    const TriangleMesh &ma = a.levels[l].rest, &mb = b.levels[l].rest;
    ASSERT_EQ(ma.num_vertices(), mb.num_vertices());
    ASSERT_EQ(ma.num_faces(), mb.num_faces());
    EXPECT_EQ(std::memcmp(ma.vertices.data(), mb.vertices.data(), ma.vertices.size() * 8), 0);
    EXPECT_EQ(ma.faces, mb.faces);
    EXPECT_EQ(a.levels[l].input_vertex, b.levels[l].input_vertex);
  }
  expect_same_anchors(a.to_next, b.to_next);
  expect_same_anchors(a.to_finest, b.to_finest);
  ASSERT_EQ(a.collapses.size(), b.collapses.size());
  for (std::size_t c = 0; c < a.collapses.size(); ++c) {
    EXPECT_EQ(a.collapses[c].removed, b.collapses[c].removed) << "collapse " << c;
    EXPECT_EQ(a.collapses[c].kept, b.collapses[c].kept) << "collapse " << c;
    EXPECT_EQ(a.collapses[c].before, b.collapses[c].before) << "collapse " << c;
    EXPECT_EQ(a.collapses[c].after, b.collapses[c].after) << "collapse " << c;
  }
  EXPECT_EQ(a.first_collapse, b.first_collapse);
  EXPECT_EQ(a.expansion_batches, b.expansion_batches);
  EXPECT_EQ(a.input_group, b.input_group);
}

/// Expects check_hierarchy_structure to reject square_hierarchy() after `change`.
void expect_rejected(const std::function<void(MeshHierarchy&)>& change,
                     std::initializer_list<std::string> parts) {
  MeshHierarchy h = square_hierarchy();
  change(h);
  expect_error([&] { check_hierarchy_structure(h); }, Status::invalid_argument, parts);
}

}  // namespace

class HierarchyIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("progsim_hierarchy_io_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// The bytes of a saved square_hierarchy() (a well-formed file, small enough to corrupt
  /// at every byte).
  std::string saved_bytes() const {
    save_hierarchy(square_hierarchy(), path("valid.pshier"));
    std::ifstream in(path("valid.pshier"), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
  }

  /// Writes `bytes` to a file in the temporary directory and returns its path.
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return path(name);
  }

  fs::path dir_;
};

namespace {

/// `bytes` with the 8 bytes at `offset` replaced by `value` (little-endian).
std::string with_int64(std::string bytes, std::size_t offset, std::int64_t value) {
  std::memcpy(&bytes[offset], &value, sizeof(value));
  return bytes;
}

}  // namespace

TEST(CheckHierarchy, AcceptsTheHandMadeHierarchies) {
  EXPECT_NO_THROW(check_hierarchy_structure(square_hierarchy()));
  EXPECT_NO_THROW(check_hierarchy_structure(single_level_hierarchy()));
}

TEST(CheckHierarchy, RejectsBadLevels) {
  expect_rejected([](MeshHierarchy& h) { h = MeshHierarchy(); }, {"no levels"});
  expect_rejected([](MeshHierarchy& h) { h.levels[1].rest.vertices(3, 1) = NAN; },
                  {"level 1 vertex 3", "non-finite"});
  expect_rejected([](MeshHierarchy& h) { h.levels[0].rest.faces(1, 2) = 4; },
                  {"level 0 face 1", "vertex 4", "4 vertices"});
  expect_rejected([](MeshHierarchy& h) { h.levels[0].input_vertex.pop_back(); },
                  {"level 0 has 3 input_vertex entries for 4 vertices"});
  expect_rejected(
      [](MeshHierarchy& h) {
        h.levels[0].input_vertex = {0, 6, 2, 8};
      },
      {"level 0 input_vertex is not strictly increasing at entry 2"});
  expect_rejected([](MeshHierarchy& h) { h.levels[0].input_vertex[3] = 9; },
                  {"level 0 input_vertex[3] = 9", "[0, 9)"});
  expect_rejected([](MeshHierarchy& h) { h.levels[1].input_vertex = {0, 1, 2, 3, 4, 5, 6, 7, 9}; },
                  {"level 1 input_vertex[8] = 9", "[0, 9)"});  // finest: must be the identity
}

TEST(CheckHierarchy, RejectsNonIncreasingLevelSizes) {
  expect_rejected([](MeshHierarchy& h) { h.levels[0] = h.levels[1]; },
                  {"level 1 has 9 vertices, not more than level 0's 9"});
}

TEST(CheckHierarchy, RejectsAnchorFaceOutOfRange) {
  expect_rejected([](MeshHierarchy& h) { h.to_next[0][3].face = 2; },
                  {"to_next[0] anchor 3", "face 2", "2 faces"});
  expect_rejected([](MeshHierarchy& h) { h.to_finest[0][7].face = -1; },
                  {"to_finest[0] anchor 7", "face -1"});
}

TEST(CheckHierarchy, RejectsBadWeights) {
  expect_rejected([](MeshHierarchy& h) { h.to_next[0][5].weights[0] += 1e-6; },
                  {"to_next[0] anchor 5", "not summing to 1"});
  expect_rejected([](MeshHierarchy& h) { h.to_finest[0][4].weights = Vec3(1.5, -0.5, 0.0); },
                  {"to_finest[0] anchor 4", "negative"});
  expect_rejected([](MeshHierarchy& h) { h.to_finest[0][2].weights[1] = INFINITY; },
                  {"to_finest[0] anchor 2", "finite"});
  expect_rejected([](MeshHierarchy& h) { h.to_next[0].pop_back(); },
                  {"to_next[0] has 8 anchors, not 9"});
  expect_rejected([](MeshHierarchy& h) { h.to_finest.clear(); }, {"to_finest has 0 entries"});
}

TEST(CheckHierarchy, AcceptsWeightsWithinRounding) {
  MeshHierarchy h = square_hierarchy();
  h.to_next[0][4].weights = Vec3(0.5 + 5e-10, -5e-10, 0.5);
  EXPECT_NO_THROW(check_hierarchy_structure(h));
}

TEST(CheckHierarchy, RejectsWrongFirstCollapse) {
  expect_rejected(
      [](MeshHierarchy& h) {
        h.first_collapse = {4, 0};
      },
      {"first_collapse[0] is 4, but there are 5 collapses"});
  expect_rejected(
      [](MeshHierarchy& h) {
        h.first_collapse = {5, 1};
      },
      {"first_collapse[1] is 1, not 0"});
  expect_rejected([](MeshHierarchy& h) { h.first_collapse = {5}; },
                  {"first_collapse has 1 entries for 2 levels"});
  expect_rejected(
      [](MeshHierarchy& h) {
        h.collapses.pop_back();
        h.first_collapse = {4, 0};
        h.expansion_batches = {{{0, 1, 2}, {3}}};
      },
      {"gives level 0 4 collapses, but level 1 has 5 more vertices"});
}

TEST(CheckHierarchy, RejectsRecordIdsOutOfRange) {
  expect_rejected([](MeshHierarchy& h) { h.collapses[2].removed = 9; },
                  {"collapse 2 removed is vertex 9"});
  expect_rejected([](MeshHierarchy& h) { h.collapses[0].kept = -1; },
                  {"collapse 0 kept is vertex -1"});
  expect_rejected([](MeshHierarchy& h) { h.collapses[4].after[1][2] = 9; },
                  {"collapse 4 after[1] corner 2 is vertex 9"});
  expect_rejected([](MeshHierarchy& h) { h.collapses[3].before[0][0] = -2; },
                  {"collapse 3 before[0] corner 0 is vertex -2"});
}

TEST(CheckHierarchy, RejectsMalformedGroups) {
  expect_rejected([](MeshHierarchy& h) { h.input_group.pop_back(); },
                  {"input_group has 8 entries for 9 input vertices"});
  expect_rejected([](MeshHierarchy& h) { h.input_group[4] = -2; }, {"input_group[4] = -2"});
}

TEST(CheckHierarchy, RejectsBatchMissingARecord) {
  expect_rejected([](MeshHierarchy& h) { h.expansion_batches[0][1] = {3}; },
                  {"expansion_batches[0] misses collapse 4"});
}

TEST(CheckHierarchy, RejectsDuplicatedRecordInBatches) {
  expect_rejected(
      [](MeshHierarchy& h) {
        h.expansion_batches[0][1] = {3, 4, 1};
      },
      {"expansion_batches[0] batch 1 repeats collapse 1"});
}

TEST(CheckHierarchy, RejectsBatchEntriesOutsideTheLevel) {
  expect_rejected([](MeshHierarchy& h) { h.expansion_batches[0][0].push_back(5); },
                  {"batch 0 holds collapse 5", "[0, 5)"});
  expect_rejected([](MeshHierarchy& h) { h.expansion_batches.clear(); },
                  {"expansion_batches has 0 entries"});
}

TEST_F(HierarchyIo, RoundTripsEveryFieldExactly) {
  for (const MeshHierarchy& h : {built_hierarchy(), single_level_hierarchy()}) {
    SCOPED_TRACE(std::to_string(h.num_levels()) + " levels");
    save_hierarchy(h, path("h.pshier"));
    expect_same_hierarchy(load_hierarchy(path("h.pshier")), h);
  }
}

TEST_F(HierarchyIo, SaveReportsUnwritablePaths) {
  const std::string missing_dir = path("no_such_dir/h.pshier");
  expect_error([&] { save_hierarchy(built_hierarchy(), missing_dir); }, Status::io_error,
               {missing_dir, "cannot open"});
  // The file is written beside the target, then renamed over it: a directory in the way makes
  // the rename fail, and nothing is left behind.
  const std::string directory = path("occupied");
  fs::create_directories(directory);
  expect_error([&] { save_hierarchy(built_hierarchy(), directory); }, Status::io_error,
               {directory, "cannot write"});
  EXPECT_FALSE(fs::exists(directory + ".partial"));
  EXPECT_TRUE(fs::is_directory(directory));
}

TEST_F(HierarchyIo, RejectsMissingEmptyAndForeignFiles) {
  const std::string missing = path("missing.pshier");
  expect_error([&] { load_hierarchy(missing); }, Status::io_error, {missing, "no such file"});
  expect_error([&] { load_hierarchy(dir_.string()); }, Status::io_error, {"not a regular file"});
  const std::string empty = write("empty.pshier", "");
  expect_error([&] { load_hierarchy(empty); }, Status::io_error, {empty, "truncated"});
  std::string bytes = saved_bytes();
  bytes[0] = 'X';
  const std::string foreign = write("foreign.pshier", bytes);
  expect_error([&] { load_hierarchy(foreign); }, Status::io_error, {foreign, "magic"});
}

TEST_F(HierarchyIo, RejectsOtherVersionsAndByteOrders) {
  std::string bytes = saved_bytes();
  bytes[kVersionOffset] = 3;
  const std::string future = write("future.pshier", bytes);
  expect_error([&] { load_hierarchy(future); }, Status::io_error, {future, "version 3"});
  bytes[kVersionOffset] = 1;  // before vertex groups were stored
  const std::string old = write("old.pshier", bytes);
  expect_error([&] { load_hierarchy(old); }, Status::io_error, {old, "version 1"});
  bytes = saved_bytes();
  std::swap(bytes[10], bytes[13]);  // the marker 0x01020304 read in the other byte order
  std::swap(bytes[11], bytes[12]);
  const std::string swapped = write("swapped.pshier", bytes);
  expect_error([&] { load_hierarchy(swapped); }, Status::io_error, {swapped, "byte-order"});
}

TEST_F(HierarchyIo, RejectsEveryTruncation) {
  const std::string bytes = saved_bytes();
  ASSERT_GT(bytes.size(), kFirstVertexCountOffset);
  int wrong = 0;
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    const std::string file = write("prefix.pshier", bytes.substr(0, size));
    try {
      load_hierarchy(file);
      ADD_FAILURE() << "the " << size << "-byte prefix loaded";
    } catch (const Error& e) {
      if (e.status() != Status::io_error && ++wrong <= 5)
        ADD_FAILURE() << size << " bytes: " << status_name(e.status()) << ": " << e.what();
    }
  }
  EXPECT_EQ(wrong, 0);
}

TEST_F(HierarchyIo, RejectsTrailingBytes) {
  const std::string file = write("long.pshier", saved_bytes() + '\0');
  expect_error([&] { load_hierarchy(file); }, Status::io_error, {file, "1 unexpected bytes"});
}

TEST_F(HierarchyIo, RejectsHugeAndNegativeCountsWithoutAllocating) {
  const std::string bytes = saved_bytes();
  for (const std::size_t offset : {kLevelCountOffset, kFirstVertexCountOffset}) {
    for (const std::int64_t count :
         {std::int64_t{1} << 60, std::int64_t{INT_MAX}, std::int64_t{-1}}) {
      SCOPED_TRACE("count " + std::to_string(count) + " at byte " + std::to_string(offset));
      const std::string file = write("huge.pshier", with_int64(bytes, offset, count));
      expect_error([&] { load_hierarchy(file); }, Status::io_error,
                   {file, "declares " + std::to_string(count)});
    }
  }
}

TEST_F(HierarchyIo, SurvivesAHugeValueAtEveryOffset) {
  // Overwriting any 8 bytes with 2^60 hits every count field once: each load must fail with
  // an Error (or load finite data, for a coordinate), never crash or throw bad_alloc.
  const std::string bytes = saved_bytes();
  for (std::size_t offset = 0; offset + 8 <= bytes.size(); ++offset) {
    const std::string file =
        write("patched.pshier", with_int64(bytes, offset, std::int64_t{1} << 60));
    try {
      load_hierarchy(file);
    } catch (const Error&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "byte " << offset << ": " << e.what();
    }
  }
}

TEST_F(HierarchyIo, NamesThePathForInconsistentContents) {
  MeshHierarchy h = built_hierarchy();
  h.to_next[0][3].face = 1000;
  save_hierarchy(h, path("bad.pshier"));
  try {
    load_hierarchy(path("bad.pshier"));
    ADD_FAILURE() << "an inconsistent hierarchy loaded";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::invalid_argument);
    EXPECT_EQ(
        std::string(e.what()).rfind(path("bad.pshier") + ": hierarchy: to_next[0] anchor 3", 0), 0u)
        << e.what();
  }
}

// Files whose shape is right but whose batches or records do not refine the levels are
// rejected: batches out of order, and a coarse face turned over.
TEST_F(HierarchyIo, RejectsBatchesAndRecordsThatDoNotRefineTheLevels) {
  MeshHierarchy h = built_hierarchy();
  ASSERT_GE(h.expansion_batches[0].size(), 2u);
  std::swap(h.expansion_batches[0].front(), h.expansion_batches[0].back());
  save_hierarchy(h, path("reordered.pshier"));
  expect_error([&] { load_hierarchy(path("reordered.pshier")); }, Status::invalid_argument,
               {"reordered.pshier", "expansion batches of level 0 differ"});
  h = built_hierarchy();
  std::swap(h.collapses[h.first_collapse[1]].after[0][0],
            h.collapses[h.first_collapse[1]].after[0][1]);
  save_hierarchy(h, path("turned.pshier"));
  expect_error([&] { load_hierarchy(path("turned.pshier")); }, Status::invalid_argument,
               {"turned.pshier"});
}
