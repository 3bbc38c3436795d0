#include "hierarchy/expansion_coloring.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <string>
#include <unordered_map>

#include "common/error.hpp"

namespace progsim {
namespace {

/// The face rotated so that its smallest corner comes first (orientation kept).
FaceCorners normalized(const FaceCorners& face) {
  const auto k = std::min_element(face.begin(), face.end()) - face.begin();
  return {face[k], face[(k + 1) % 3], face[(k + 2) % 3]};
}

std::string face_name(const FaceCorners& face) {
  return "(" + std::to_string(face[0]) + ", " + std::to_string(face[1]) + ", " +
         std::to_string(face[2]) + ")";
}

/// Hash of a corner triple: the corners packed, then mixed by the splitmix64 finaliser.
struct FaceHash {
  std::size_t operator()(const FaceCorners& face) const {
    std::uint64_t hash = 0;
    for (const int corner : face)
      hash = hash * 0x100000001B3ull + static_cast<std::uint32_t>(corner);
    hash = (hash ^ (hash >> 30)) * 0xBF58476D1CE4E5B9ull;
    hash = (hash ^ (hash >> 27)) * 0x94D049BB133111EBull;
    return static_cast<std::size_t>(hash ^ (hash >> 31));
  }
};

/// Dense ids of rotation-normalised faces.
class FaceIds {
 public:
  explicit FaceIds(std::size_t capacity) {
    ids_.reserve(capacity);
    faces_.reserve(capacity);
  }

  /// The id of `face`, new if unseen.
  int intern(const FaceCorners& face) {
    const auto [it, fresh] = ids_.emplace(normalized(face), static_cast<int>(faces_.size()));
    if (fresh) faces_.push_back(it->first);
    return it->second;
  }

  /// Per id, the normalised face.
  std::vector<FaceCorners> take_faces() && { return std::move(faces_); }

 private:
  std::unordered_map<FaceCorners, int, FaceHash> ids_;
  std::vector<FaceCorners> faces_;
};

/// Lists of ids stored back to back: list i is ids[offset[i], offset[i + 1]).
class IdLists {
 public:
  struct Range {
    const int* first;
    const int* last;
    const int* begin() const { return first; }
    const int* end() const { return last; }
  };

  void push_back(int id) { ids_.push_back(id); }
  void end_list() { offset_.push_back(static_cast<int>(ids_.size())); }
  int size() const { return static_cast<int>(offset_.size()) - 1; }
  Range operator[](int i) const { return {ids_.data() + offset_[i], ids_.data() + offset_[i + 1]}; }

  /// The inverse relation: list j of the result holds every i whose list holds j (< targets).
  IdLists transposed(int targets) const {
    IdLists out;
    out.offset_.assign(targets + 1, 0);
    for (const int id : ids_) ++out.offset_[id + 1];
    std::partial_sum(out.offset_.begin(), out.offset_.end(), out.offset_.begin());
    out.ids_.resize(ids_.size());
    std::vector<int> next(out.offset_.begin(), out.offset_.end() - 1);
    for (int i = 0; i < size(); ++i)
      for (const int id : (*this)[i]) out.ids_[next[id]++] = i;
    return out;
  }

 private:
  std::vector<int> offset_{0};
  std::vector<int> ids_;
};

/// Appends the ids of `faces` as one more list.
void add_list(FaceIds& ids, const std::vector<FaceCorners>& faces, IdLists& lists) {
  for (const FaceCorners& face : faces) lists.push_back(ids.intern(face));
  lists.end_list();
}

/// Greedy coloring of the splits [first, last) on the expanding mesh M_d (PSQ Algorithms 6–7).
/// Splits are numbered locally (record index − first). A pending split is ready when
///  - all of its `after` faces are in M_d (every later collapse that destroyed one is undone), and
///  - no other pending split lists among its `after` faces a face this split destroys (a later
///    collapse that kept a face created by this one must be undone first, or that face would be
///    gone for good when it needs it).
class SplitScheduler {
 public:
  SplitScheduler(const std::vector<FaceCorners>& coarse_faces,
                 const std::vector<CollapseRecord>& collapses, int first, int last);

  /// Algorithm 6: independent sets of ready splits, each expanded before the next is built.
  std::vector<std::vector<int>> run();

 private:
  void add_vertex(int vertex);
  void count_blockers();
  void insert_face(int face);
  void erase_face(int face);
  void queue_if_ready(int split);
  template <class Visit>
  void for_each_ring_vertex(int split, Visit visit) const;
  std::vector<int> independent_set();
  void expand(int split);
  [[noreturn]] void fail_stuck() const;

  const std::vector<CollapseRecord>& collapses_;
  const int first_;
  std::vector<FaceCorners> faces_;      ///< per face id: its normalised corners
  std::vector<int> copies_;             ///< per face id: copies in M_d
  IdLists waiting_;                     ///< per face id: splits with it among `after`
  std::vector<int> created_by_;         ///< per face id: the collapse that created it, or −1
  std::vector<std::vector<int>> star_;  ///< per vertex: ids of the faces of M_d around it
  std::vector<int> in_set_round_;       ///< per vertex: last round it joined the set N
  IdLists before_, after_;              ///< per split: face ids
  std::vector<int> missing_;            ///< per split: `after` faces not in M_d
  std::vector<int> blockers_;           ///< per split: pending (face it destroys, other user) pairs
  std::vector<char> pending_, queued_;  ///< per split
  std::vector<int> ready_;              ///< queued splits, possibly no longer ready
  int round_ = 0;
};

SplitScheduler::SplitScheduler(const std::vector<FaceCorners>& coarse_faces,
                               const std::vector<CollapseRecord>& collapses, int first, int last)
    : collapses_(collapses), first_(first) {
  std::size_t total = coarse_faces.size();
  for (int r = first; r < last; ++r)
    total += collapses[r].before.size() + collapses[r].after.size();
  FaceIds ids(total);
  for (int r = first; r < last; ++r) {
    add_vertex(collapses[r].kept);
    add_vertex(collapses[r].removed);
    add_list(ids, collapses[r].before, before_);
    add_list(ids, collapses[r].after, after_);
  }
  IdLists coarse;
  add_list(ids, coarse_faces, coarse);
  faces_ = std::move(ids).take_faces();
  for (const FaceCorners& face : faces_)
    for (const int corner : face) add_vertex(corner);
  const int splits = last - first;
  copies_.assign(faces_.size(), 0);
  waiting_ = after_.transposed(static_cast<int>(faces_.size()));
  in_set_round_.assign(star_.size(), 0);
  missing_.resize(splits);
  for (int s = 0; s < splits; ++s)
    missing_[s] = static_cast<int>(collapses[first + s].after.size());
  pending_.assign(splits, 1);
  queued_.assign(splits, 0);
  count_blockers();
  for (const int face : coarse[0]) insert_face(face);
  for (int s = 0; s < splits; ++s) queue_if_ready(s);
}

void SplitScheduler::add_vertex(int vertex) {
  if (vertex < 0)
    fail(Status::internal, "expansion_batches: negative vertex id " + std::to_string(vertex));
  if (vertex >= static_cast<int>(star_.size())) star_.resize(vertex + 1);
}

/// Fills created_by_ (a face in a record's `after` but not its `before` is created by that
/// collapse and destroyed by its split) and blockers_.
void SplitScheduler::count_blockers() {
  created_by_.assign(faces_.size(), -1);
  for (int s = 0; s < after_.size(); ++s)
    for (const int face : after_[s]) {
      if (std::count(before_[s].begin(), before_[s].end(), face) > 0) continue;
      if (created_by_[face] >= 0)
        fail(Status::internal, "expansion_batches: collapse records " +
                                   std::to_string(first_ + created_by_[face]) + " and " +
                                   std::to_string(first_ + s) + " both create the face " +
                                   face_name(faces_[face]));
      created_by_[face] = s;
    }
  blockers_.assign(after_.size(), 0);
  for (int s = 0; s < after_.size(); ++s)
    for (const int face : after_[s])
      if (created_by_[face] >= 0 && created_by_[face] != s) ++blockers_[created_by_[face]];
}

void SplitScheduler::insert_face(int face) {
  if (copies_[face]++ > 0) return;
  for (const int corner : faces_[face]) star_[corner].push_back(face);
  for (const int split : waiting_[face])
    if (--missing_[split] == 0) queue_if_ready(split);
}

void SplitScheduler::erase_face(int face) {
  if (--copies_[face] > 0) return;
  for (const int corner : faces_[face]) {
    std::vector<int>& star = star_[corner];
    *std::find(star.begin(), star.end(), face) = star.back();
    star.pop_back();
  }
  for (const int split : waiting_[face]) ++missing_[split];
}

void SplitScheduler::queue_if_ready(int split) {
  if (!pending_[split] || queued_[split] || missing_[split] > 0 || blockers_[split] > 0) return;
  queued_[split] = 1;
  ready_.push_back(split);
}

/// Visits R of Algorithm 7, possibly repeating vertices: the closed one-ring of `kept` in M_d
/// and the vertices of the `before` faces, which contain the future one-ring of `removed`.
template <class Visit>
void SplitScheduler::for_each_ring_vertex(int split, Visit visit) const {
  const int kept = collapses_[first_ + split].kept;
  visit(kept);
  for (const int face : star_[kept])
    for (const int v : faces_[face]) visit(v);
  for (const int face : before_[split])
    for (const int v : faces_[face]) visit(v);
}

/// Algorithm 7 over the ready splits, latest in decimation order first: a split joins the set s
/// if its R misses the set N of vertices claimed so far. Splits that lost an `after` face leave
/// the queue (they are queued again when it returns); rejected ones stay queued.
std::vector<int> SplitScheduler::independent_set() {
  ++round_;
  std::vector<int> candidates;
  candidates.swap(ready_);
  std::sort(candidates.rbegin(), candidates.rend());
  std::vector<int> set;
  for (const int split : candidates) {
    if (missing_[split] > 0) {
      queued_[split] = 0;
      continue;
    }
    bool free = true;
    for_each_ring_vertex(split, [&](int v) { free = free && in_set_round_[v] != round_; });
    if (!free) {
      ready_.push_back(split);
      continue;
    }
    for_each_ring_vertex(split, [&](int v) { in_set_round_[v] = round_; });
    set.push_back(split);
  }
  return set;
}

/// Undoes the collapse in M_d and releases the splits that waited for it.
void SplitScheduler::expand(int split) {
  pending_[split] = 0;
  queued_[split] = 0;
  for (const int face : after_[split]) erase_face(face);
  for (const int face : before_[split]) insert_face(face);
  for (const int face : after_[split]) {
    const int owner = created_by_[face];
    if (owner >= 0 && owner != split && --blockers_[owner] == 0) queue_if_ready(owner);
  }
}

void SplitScheduler::fail_stuck() const {
  const auto stuck = std::find(pending_.begin(), pending_.end(), 1) - pending_.begin();
  fail(Status::internal, "expansion_batches: the split of collapse record " +
                             std::to_string(first_ + stuck) +
                             " never becomes ready: the records do not match the coarse faces");
}

std::vector<std::vector<int>> SplitScheduler::run() {
  std::vector<std::vector<int>> batches;
  for (std::size_t remaining = pending_.size(); remaining > 0;) {
    std::vector<int> batch = independent_set();
    if (batch.empty()) fail_stuck();
    for (int& split : batch) {
      expand(split);
      split += first_;
    }
    remaining -= batch.size();
    batches.push_back(std::move(batch));
  }
  return batches;
}

/// The faces rotation-normalised and sorted (left alone if they already are).
void normalize_and_sort(std::vector<FaceCorners>& faces) {
  bool sorted = true;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const FaceCorners face = normalized(faces[f]);
    sorted = sorted && face == faces[f] && (f == 0 || faces[f - 1] <= face);
    faces[f] = face;
  }
  if (!sorted) std::sort(faces.begin(), faces.end());
}

/// The normalised `after` (or `before`) faces of the batch, sorted.
std::vector<FaceCorners> batch_faces(const std::vector<CollapseRecord>& collapses,
                                     const std::vector<int>& batch, bool after) {
  std::vector<FaceCorners> faces;
  for (const int record : batch) {
    if (record < 0 || record >= static_cast<int>(collapses.size()))
      fail(Status::invalid_argument, "apply_splits: record " + std::to_string(record) +
                                         " outside the " + std::to_string(collapses.size()) +
                                         " collapse records");
    const std::vector<FaceCorners>& list =
        after ? collapses[record].after : collapses[record].before;
    faces.insert(faces.end(), list.begin(), list.end());
  }
  normalize_and_sort(faces);
  return faces;
}

/// Throws Error(internal) naming a face of `removed` (sorted) that `faces` (sorted) lacks and a
/// split of `batch` that needs it.
void check_present(const std::vector<FaceCorners>& faces, const std::vector<FaceCorners>& removed,
                   const std::vector<CollapseRecord>& collapses, const std::vector<int>& batch) {
  std::vector<FaceCorners> missing;
  std::set_difference(removed.begin(), removed.end(), faces.begin(), faces.end(),
                      std::back_inserter(missing));
  if (missing.empty()) return;
  const auto needs = [&](int record) {
    const std::vector<FaceCorners>& after = collapses[record].after;
    return std::any_of(after.begin(), after.end(),
                       [&](const FaceCorners& face) { return normalized(face) == missing[0]; });
  };
  fail(Status::internal, "apply_splits: the face " + face_name(missing[0]) + " of split " +
                             std::to_string(*std::find_if(batch.begin(), batch.end(), needs)) +
                             " is not in the mesh");
}

}  // namespace

std::vector<std::vector<int>> expansion_batches(const std::vector<FaceCorners>& coarse_faces,
                                                const std::vector<CollapseRecord>& collapses,
                                                int first, int last) {
  if (first < 0 || last < first || last > static_cast<int>(collapses.size()))
    fail(Status::invalid_argument, "expansion_batches: records [" + std::to_string(first) + ", " +
                                       std::to_string(last) + ") outside the " +
                                       std::to_string(collapses.size()) + " collapse records");
  return SplitScheduler(coarse_faces, collapses, first, last).run();
}

void apply_splits(std::vector<FaceCorners>& faces, const std::vector<CollapseRecord>& collapses,
                  const std::vector<int>& batch) {
  const std::vector<FaceCorners> removed = batch_faces(collapses, batch, true);
  const std::vector<FaceCorners> added = batch_faces(collapses, batch, false);
  normalize_and_sort(faces);
  check_present(faces, removed, collapses, batch);
  std::vector<FaceCorners> kept;
  kept.reserve(faces.size() - removed.size());
  std::set_difference(faces.begin(), faces.end(), removed.begin(), removed.end(),
                      std::back_inserter(kept));
  faces.clear();
  std::merge(kept.begin(), kept.end(), added.begin(), added.end(), std::back_inserter(faces));
}

bool same_faces(std::vector<FaceCorners> a, std::vector<FaceCorners> b) {
  normalize_and_sort(a);
  normalize_and_sort(b);
  return a == b;
}

}  // namespace progsim
