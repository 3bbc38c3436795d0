#include "contact/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "common/parallel.hpp"

namespace progsim {
namespace {

struct Box {
  Vec3 lo, hi;
};

using Key = std::uint64_t;

bool overlap(const Box& a, const Box& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

/// Box of the primitive with vertices idx[0..K) over the motion p0 → p1, grown by r.
template <int K>
Box swept_box(const int* idx, const Positions& p0, const Positions& p1, double r) {
  Box box{Vec3::Constant(std::numeric_limits<double>::infinity()),
          Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (int k = 0; k < K; ++k)
    for (const Positions* p : {&p0, &p1}) {
      box.lo = box.lo.cwiseMin(p->row(idx[k]).transpose());
      box.hi = box.hi.cwiseMax(p->row(idx[k]).transpose());
    }
  box.lo.array() -= r;
  box.hi.array() += r;
  return box;
}

template <int K, class IndexOf>
std::vector<Box> boxes(int count, IndexOf index_of, const Positions& p0, const Positions& p1,
                       double r) {
  std::vector<Box> out(count);
#pragma omp parallel for schedule(static) if (count >= kMinParallelItems)
  for (int i = 0; i < count; ++i) out[i] = swept_box<K>(index_of(i), p0, p1, r);
  return out;
}

/// A uniform grid over boxes (a spatial hash with sorted keys): each box is listed in every
/// cell it overlaps; boxes spanning more than kMaxCells cells are kept apart as "large".
class BoxGrid {
 public:
  static constexpr long kMaxCells = 64;

  BoxGrid(const std::vector<Box>& boxes, double cell) : inverse_cell_(1.0 / cell) {
    const int n = static_cast<int>(boxes.size());
    std::vector<long> offsets(n + 1, 0);
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
    for (int i = 0; i < n; ++i) {
      const long c = cell_count(boxes[i]);
      offsets[i + 1] = c <= kMaxCells ? c : 0;
    }
    for (int i = 0; i < n; ++i) {
      if (is_large(boxes[i])) large_.push_back(i);
      offsets[i + 1] += offsets[i];
    }
    entries_.resize(offsets[n]);
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
    for (int i = 0; i < n; ++i) {
      long k = offsets[i];
      if (offsets[i + 1] > k) for_each_cell(boxes[i], [&](Key key) { entries_[k++] = {key, i}; });
    }
    std::sort(entries_.begin(), entries_.end());
  }

  bool is_large(const Box& b) const {
    return cell_count(b) > kMaxCells;
  }
  const std::vector<int>& large() const {
    return large_;
  }

  /// The cell holding point x.
  Key cell_of(const Vec3& x) const {
    return key(index(x.x()), index(x.y()), index(x.z()));
  }

  /// Calls visit(key) for every cell the box overlaps.
  template <class Visit>
  void for_each_cell(const Box& b, Visit visit) const {
    for (long i = index(b.lo.x()); i <= index(b.hi.x()); ++i)
      for (long j = index(b.lo.y()); j <= index(b.hi.y()); ++j)
        for (long k = index(b.lo.z()); k <= index(b.hi.z()); ++k) visit(key(i, j, k));
  }

  /// Calls visit(box) for every small box listed in cell `key`.
  template <class Visit>
  void for_each_in_cell(Key key, Visit visit) const {
    auto it = std::lower_bound(entries_.begin(), entries_.end(), Entry{key, -1});
    for (; it != entries_.end() && it->key == key; ++it) visit(it->box);
  }

 private:
  struct Entry {
    Key key;
    int box;
    bool operator<(const Entry& o) const { return key != o.key ? key < o.key : box < o.box; }
  };

  /// Cell index along an axis, clamped so that huge coordinates cannot overflow the cast.
  long index(double x) const {
    return static_cast<long>(std::clamp(std::floor(x * inverse_cell_), -1e15, 1e15));
  }

  /// 21 bits per axis; distant cells that wrap onto one key only cost extra box tests.
  static Key key(long i, long j, long k) {
    constexpr long mask = (1L << 21) - 1;
    return (static_cast<Key>(i & mask) << 42) | (static_cast<Key>(j & mask) << 21) |
           static_cast<Key>(k & mask);
  }

  long cell_count(const Box& b) const {
    long count = 1;
    for (int a = 0; a < 3; ++a) {
      count *= index(b.hi[a]) - index(b.lo[a]) + 1;
      if (count > kMaxCells) return kMaxCells + 1;
    }
    return count;
  }

  double inverse_cell_;
  std::vector<Entry> entries_;
  std::vector<int> large_;
};

/// Every (query, target) whose boxes overlap and that `accept` keeps, sorted. A pair of small
/// boxes is reported from exactly one cell, the one holding the lower corner of their overlap;
/// a large box is tested against every box of the other set.
template <class Accept>
std::vector<std::array<int, 2>> overlapping_pairs(const std::vector<Box>& queries,
                                                  const std::vector<Box>& targets, double cell,
                                                  Accept accept) {
  const BoxGrid grid(targets, cell);
  std::vector<std::array<int, 2>> pairs;
  const int n = static_cast<int>(queries.size());
#pragma omp parallel if (n >= kMinParallelItems)
  {
    std::vector<std::array<int, 2>> local;
#pragma omp for schedule(dynamic, 256) nowait
    for (int q = 0; q < n; ++q) {
      const Box& box = queries[q];
      auto consider = [&](int t) {
        if (overlap(box, targets[t]) && accept(q, t)) local.push_back({q, t});
      };
      if (grid.is_large(box)) {
        for (int t = 0; t < static_cast<int>(targets.size()); ++t) consider(t);
        continue;
      }
      for (int t : grid.large()) consider(t);
      grid.for_each_cell(box, [&](Key key) {
        grid.for_each_in_cell(key, [&](int t) {
          if (grid.cell_of(box.lo.cwiseMax(targets[t].lo)) == key) consider(t);
        });
      });
    }
#pragma omp critical
    pairs.insert(pairs.end(), local.begin(), local.end());
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// Grid cell size: the mean largest extent of the boxes (at least the inflation).
double cell_size(const std::vector<Box>& boxes, double inflation) {
  double sum = 0.0;
  for (const Box& b : boxes) sum += (b.hi - b.lo).maxCoeff();
  return std::max(boxes.empty() ? 1.0 : sum / static_cast<double>(boxes.size()), inflation);
}

}  // namespace

void find_candidates(const CollisionMesh& mesh, const Positions& p0, const Positions& p1,
                     double inflation, CandidateSet& out) {
  const double r = 0.5 * inflation;  // two boxes grown by r overlap iff gap ≤ 2r per axis
  const int nv = mesh.num_vertices();
  const int nf = static_cast<int>(mesh.faces.rows());
  const int ne = static_cast<int>(mesh.edges.size());
  std::vector<int> vertex_ids(nv);
  for (int v = 0; v < nv; ++v) vertex_ids[v] = v;
  const auto vertex_boxes = boxes<1>(
      nv, [&](int v) { return &vertex_ids[v]; }, p0, p1, r);
  const auto face_boxes = boxes<3>(
      nf, [&](int f) { return mesh.faces.row(f).data(); }, p0, p1, r);
  const auto edge_boxes = boxes<2>(
      ne, [&](int e) { return mesh.edges[e].data(); }, p0, p1, r);
  const double cell = cell_size(edge_boxes, inflation);
  out.vertex_face = overlapping_pairs(vertex_boxes, face_boxes, cell, [&](int v, int f) {
    const auto face = mesh.faces.row(f);
    if (face[0] == v || face[1] == v || face[2] == v) return false;
    return !(mesh.is_obstacle(v) && mesh.is_obstacle(face[0]));
  });
  out.edge_edge = overlapping_pairs(edge_boxes, edge_boxes, cell, [&](int a, int b) {
    if (b <= a) return false;
    const auto& ea = mesh.edges[a];
    const auto& eb = mesh.edges[b];
    if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) return false;
    return !(mesh.is_obstacle(ea[0]) && mesh.is_obstacle(eb[0]));
  });
}

}  // namespace progsim
