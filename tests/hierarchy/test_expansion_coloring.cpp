// Expansion coloring: schedules of vertex splits built from random edge collapses on a grid
// cover every split once, keep the rings of a batch disjoint, respect the collapse dependencies
// and replay exactly to the fine mesh; inconsistent records are reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "hierarchy/expansion_coloring.hpp"

using namespace progsim;

namespace {

/// The face rotated so that its smallest corner comes first (independent of the module's).
FaceCorners rotated_to_min(const FaceCorners& f) {
  const int k = static_cast<int>(std::min_element(f.begin(), f.end()) - f.begin());
  return {f[k], f[(k + 1) % 3], f[(k + 2) % 3]};
}

std::set<FaceCorners> face_set(const std::vector<FaceCorners>& faces) {
  std::set<FaceCorners> set;
  for (const FaceCorners& f : faces) set.insert(rotated_to_min(f));
  return set;
}

/// Random edge collapses on an n × n vertex grid (a stand-in for the decimator): interior edges
/// whose endpoints are both off the border and that satisfy the link condition.
class GridDecimator {
 public:
  GridDecimator(int n, unsigned seed) : n_(n), rng_(seed), star_(n * n) {
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        const int v00 = i * n + j, v10 = v00 + n, v01 = v00 + 1, v11 = v10 + 1;
        add_face({v00, v10, v11});
        add_face({v00, v11, v01});
      }
    for (int v = 0; v < n * n; ++v)
      if (!on_border(v)) candidates_.push_back(v);
  }

  /// Performs `count` more collapses (fails the test if it cannot).
  void collapse(int count) {
    for (int done = 0, attempts = 0; done < count; ++attempts) {
      ASSERT_LT(attempts, 1000 * count + 100000) << "grid too small for the collapses";
      done += try_random_collapse();
    }
  }

  std::vector<FaceCorners> faces() const {
    std::vector<FaceCorners> out;
    for (std::size_t f = 0; f < faces_.size(); ++f)
      if (alive_[f]) out.push_back(faces_[f]);
    return out;
  }
  const std::vector<CollapseRecord>& records() const { return records_; }

 private:
  bool on_border(int v) const {
    const int i = v / n_, j = v % n_;
    return i == 0 || j == 0 || i == n_ - 1 || j == n_ - 1;
  }

  void add_face(const FaceCorners& face) {
    for (const int v : face) star_[v].push_back(static_cast<int>(faces_.size()));
    faces_.push_back(face);
    alive_.push_back(1);
  }

  void remove_face(int f) {
    alive_[f] = 0;
    for (const int v : faces_[f]) star_[v].erase(std::find(star_[v].begin(), star_[v].end(), f));
  }

  std::set<int> neighbours(int v) const {
    std::set<int> out;
    for (const int f : star_[v])
      for (const int w : faces_[f])
        if (w != v) out.insert(w);
    return out;
  }

  /// Picks a random interior vertex and neighbour; collapses the edge if allowed.
  bool try_random_collapse() {
    const std::size_t pick = rng_() % candidates_.size();
    const int a = candidates_[pick];
    if (star_[a].empty()) {  // removed earlier
      candidates_[pick] = candidates_.back();
      candidates_.pop_back();
      return false;
    }
    const std::set<int> around_a = neighbours(a);
    const int b = *std::next(around_a.begin(), rng_() % around_a.size());
    if (on_border(b) || !link_condition(a, b, around_a)) return false;
    if (rng_() % 2)
      collapse_edge(a, b);
    else
      collapse_edge(b, a);
    return true;
  }

  /// The common neighbours of a and b are exactly the opposite corners of the two edge faces.
  bool link_condition(int a, int b, const std::set<int>& around_a) const {
    std::set<int> opposite;
    int edge_faces = 0;
    for (const int f : star_[a]) {
      const FaceCorners& face = faces_[f];
      if (std::find(face.begin(), face.end(), b) == face.end()) continue;
      ++edge_faces;
      for (const int w : face)
        if (w != a && w != b) opposite.insert(w);
    }
    std::set<int> common;
    for (const int w : neighbours(b))
      if (around_a.count(w)) common.insert(w);
    return edge_faces == 2 && common == opposite && opposite.size() == 2;
  }

  void collapse_edge(int removed, int kept) {
    CollapseRecord record{removed, kept, {}, {}};
    std::set<int> around(star_[removed].begin(), star_[removed].end());
    around.insert(star_[kept].begin(), star_[kept].end());
    for (const int f : around) {
      FaceCorners face = faces_[f];
      record.before.push_back(face);
      remove_face(f);
      if (std::count(face.begin(), face.end(), removed) +
              std::count(face.begin(), face.end(), kept) ==
          2)
        continue;  // the face degenerates
      std::replace(face.begin(), face.end(), removed, kept);
      record.after.push_back(face);
    }
    for (const FaceCorners& face : record.after) add_face(face);
    records_.push_back(std::move(record));
  }

  int n_;
  std::mt19937 rng_;
  std::vector<FaceCorners> faces_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> star_;
  std::vector<int> candidates_;
  std::vector<CollapseRecord> records_;
};

/// R of a split recomputed from scratch: kept, its closed one-ring in `faces`, and the vertices
/// of the split's before faces.
std::set<int> ring_of(const CollapseRecord& record, const std::vector<FaceCorners>& faces) {
  std::set<int> ring{record.kept};
  for (const FaceCorners& f : faces)
    if (std::count(f.begin(), f.end(), record.kept)) ring.insert(f.begin(), f.end());
  for (const FaceCorners& f : record.before) ring.insert(f.begin(), f.end());
  return ring;
}

/// Checks one level's schedule against the coarse faces and replays it; returns the faces
/// reached.
std::vector<FaceCorners> check_and_replay(std::vector<FaceCorners> faces,
                                          const std::vector<CollapseRecord>& records, int first,
                                          int last, const std::vector<std::vector<int>>& batches) {
  std::vector<int> seen(records.size(), 0);
  for (const std::vector<int>& batch : batches) {
    EXPECT_FALSE(batch.empty());
    const std::set<FaceCorners> current = face_set(faces);
    std::map<int, int> owner;  // vertex → record whose R holds it
    for (const int r : batch) {
      EXPECT_GE(r, first);
      EXPECT_LT(r, last);
      if (r < first || r >= last) return {};
      ++seen[r];
      for (const FaceCorners& f : records[r].after)
        EXPECT_TRUE(current.count(rotated_to_min(f))) << "split " << r << " is not ready";
      for (const int v : ring_of(records[r], faces)) {
        const auto [it, fresh] = owner.emplace(v, r);
        EXPECT_TRUE(fresh) << "splits " << it->second << " and " << r << " share vertex " << v;
      }
    }
    apply_splits(faces, records, batch);
  }
  for (int r = first; r < last; ++r) EXPECT_EQ(seen[r], 1) << "record " << r;
  return faces;
}

/// Batch of each record (−1 if none).
std::vector<int> batch_of(const std::vector<std::vector<int>>& batches, int records) {
  std::vector<int> out(records, -1);
  for (std::size_t b = 0; b < batches.size(); ++b)
    for (const int r : batches[b]) out[r] = static_cast<int>(b);
  return out;
}

/// Faces a collapse destroys (before \ after).
std::set<FaceCorners> destroyed(const CollapseRecord& record) {
  std::set<FaceCorners> out = face_set(record.before);
  for (const FaceCorners& f : face_set(record.after)) out.erase(f);
  return out;
}

/// Faces a collapse creates (after \ before).
std::set<FaceCorners> created(const CollapseRecord& record) {
  return destroyed({record.removed, record.kept, record.after, record.before});
}

bool meet(const std::set<FaceCorners>& a, const std::set<FaceCorners>& b) {
  return std::any_of(a.begin(), a.end(), [&](const FaceCorners& f) { return b.count(f) > 0; });
}

}  // namespace

TEST(SameFaces, IgnoresRotationAndOrderButNotOrientationOrMultiplicity) {
  const std::vector<FaceCorners> a{{0, 1, 2}, {2, 1, 3}, {4, 5, 6}};
  EXPECT_TRUE(same_faces(a, {{5, 6, 4}, {1, 2, 0}, {3, 2, 1}}));
  EXPECT_FALSE(same_faces(a, {{0, 2, 1}, {2, 1, 3}, {4, 5, 6}}));
  EXPECT_FALSE(same_faces(a, {{0, 1, 2}, {2, 1, 3}}));
  EXPECT_FALSE(same_faces(a, {{0, 1, 2}, {2, 1, 3}, {4, 5, 6}, {6, 4, 5}}));
  EXPECT_TRUE(same_faces({}, {}));
}

TEST(ApplySplits, UndoesACollapseAndRejectsAMissingFace) {
  // A fan of four faces around vertex 4; collapse 5 (inside face (0, 1, 4)) into 4.
  const std::vector<CollapseRecord> records{{5, 4, {{0, 1, 5}, {1, 4, 5}, {4, 0, 5}}, {{0, 1, 4}}}};
  std::vector<FaceCorners> faces{{1, 4, 0}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  apply_splits(faces, records, {0});
  EXPECT_TRUE(
      same_faces(faces, {{0, 1, 5}, {1, 4, 5}, {4, 0, 5}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}));
  for (const auto& [batch, status] : {std::pair{0, Status::internal},  // after face gone
                                      std::pair{1, Status::invalid_argument}}) {
    try {
      apply_splits(faces, records, {batch});
      ADD_FAILURE() << "no error for batch {" << batch << "}";
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), status) << e.what();
    }
  }
}

TEST(ExpansionBatches, OneLevelReplaysToTheFineMeshInFewDisjointBatches) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    GridDecimator decimator(30, seed);
    const std::vector<FaceCorners> fine = decimator.faces();
    decimator.collapse(400);
    const std::vector<FaceCorners> coarse = decimator.faces();
    const std::vector<CollapseRecord>& records = decimator.records();
    const int n = static_cast<int>(records.size());
    const auto batches = expansion_batches(coarse, records, 0, n);
    std::cout << "seed " << seed << ": " << n << " splits in " << batches.size() << " batches\n";
    EXPECT_LE(batches.size() * 10, records.size());
    EXPECT_TRUE(same_faces(check_and_replay(coarse, records, 0, n, batches), fine));
  }
}

TEST(ExpansionBatches, RunsEachSplitAfterTheLaterCollapsesThatTouchedItsFaces) {
  // Split i must wait for a later collapse j that destroyed one of its after faces, or that
  // lists a face collapse i created (undoing i first would leave j without it).
  GridDecimator decimator(30, 7);
  decimator.collapse(400);
  const std::vector<CollapseRecord>& records = decimator.records();
  const int n = static_cast<int>(records.size());
  const std::vector<int> batch = batch_of(expansion_batches(decimator.faces(), records, 0, n), n);
  int destroying = 0, keeping = 0;
  for (int i = 0; i < n; ++i) {
    const std::set<FaceCorners> after = face_set(records[i].after), made = created(records[i]);
    for (int j = i + 1; j < n; ++j) {
      const bool destroys = meet(destroyed(records[j]), after);
      const bool keeps = meet(face_set(records[j].after), made);
      destroying += destroys;
      keeping += keeps && !destroys;
      if (destroys || keeps) {
        EXPECT_LT(batch[j], batch[i]) << "split " << i << " before " << j;
      }
    }
  }
  std::cout << destroying << " destroying and " << keeping << " keeping dependencies\n";
  EXPECT_GT(destroying, n / 2);
  EXPECT_GT(keeping, n / 10);
}

TEST(ExpansionBatches, SchedulesEachLevelOfATwoLevelHierarchy) {
  GridDecimator decimator(30, 11);
  const std::vector<FaceCorners> fine = decimator.faces();
  decimator.collapse(250);
  const std::vector<FaceCorners> middle = decimator.faces();
  decimator.collapse(250);
  const std::vector<FaceCorners> coarse = decimator.faces();
  const std::vector<CollapseRecord>& records = decimator.records();
  const auto upper = expansion_batches(coarse, records, 250, 500);
  EXPECT_TRUE(same_faces(check_and_replay(coarse, records, 250, 500, upper), middle));
  const auto lower = expansion_batches(middle, records, 0, 250);
  EXPECT_TRUE(same_faces(check_and_replay(middle, records, 0, 250, lower), fine));
  EXPECT_TRUE(expansion_batches(middle, records, 250, 250).empty());
}

TEST(ExpansionBatches, ReportsRecordsThatDoNotMatchTheCoarseFaces) {
  GridDecimator decimator(20, 5);
  decimator.collapse(150);
  const std::vector<CollapseRecord>& records = decimator.records();
  const int n = static_cast<int>(records.size());
  int dropped = 0;
  for (const int r : {n - 1, n / 2, 0}) {
    // Drop the first `after` face of record r that survives into the coarse mesh.
    std::vector<FaceCorners> coarse = decimator.faces();
    const auto it = std::find_if(coarse.begin(), coarse.end(), [&](const FaceCorners& f) {
      return face_set(records[r].after).count(rotated_to_min(f)) > 0;
    });
    if (it == coarse.end()) continue;
    coarse.erase(it);
    ++dropped;
    try {
      expansion_batches(coarse, records, 0, n);
      ADD_FAILURE() << "no error after dropping a face of record " << r;
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), Status::internal) << e.what();
    }
  }
  EXPECT_GE(dropped, 1);
  for (const auto& [first, last] : {std::pair{0, n + 1}, std::pair{2, 1}, std::pair{-1, 3}}) {
    try {
      expansion_batches(decimator.faces(), records, first, last);
      ADD_FAILURE() << "no error for records [" << first << ", " << last << ")";
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), Status::invalid_argument) << e.what();
    }
  }
}
