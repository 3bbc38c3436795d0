#include "contact/broad_phase.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "common/parallel.hpp"

namespace progsim {
namespace {

struct Box {
  Vec3 lo, hi;
};

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

/// Integer cell coordinates (i, j, k) of a uniform grid.
using Cell = std::array<long, 3>;

/// A uniform grid over boxes: each box is listed in every cell it overlaps; boxes spanning more
/// than kMaxCells cells are kept apart as "large". Cells are stored densely (a counting sort
/// over the cells of the small boxes' bounding region, O(1) lookup) unless that region has
/// more than kDenseCellsPerEntry cells per listing, e.g. a far-away obstacle; then as a
/// spatial hash with sorted keys (binary-search lookup).
class BoxGrid {
 public:
  static constexpr long kMaxCells = 64;
  static constexpr long kDenseCellsPerEntry = 8;

  BoxGrid(const std::vector<Box>& boxes, double cell) : inverse_cell_(1.0 / cell) {
    const int n = static_cast<int>(boxes.size());
    lo_.resize(n);
    std::vector<Cell> hi(n);
    std::vector<long> count(n + 1, 0);
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
    for (int b = 0; b < n; ++b) {
      lo_[b] = cell_of(boxes[b].lo);
      hi[b] = cell_of(boxes[b].hi);
      count[b + 1] = cell_count(lo_[b], hi[b]);
    }
    Cell min_cell{kNoCell, kNoCell, kNoCell}, max_cell{-kNoCell, -kNoCell, -kNoCell};
    long listings = 0;
    for (int b = 0; b < n; ++b) {
      if (count[b + 1] > kMaxCells) {
        large_.push_back(b);
        continue;
      }
      listings += count[b + 1];
      for (int a = 0; a < 3; ++a) {
        min_cell[a] = std::min(min_cell[a], lo_[b][a]);
        max_cell[a] = std::max(max_cell[a], hi[b][a]);
      }
    }
    if (listings == 0) return;
    origin_ = min_cell;
    long cells = 1;
    for (int a = 0; a < 3 && cells > 0; ++a) {
      extent_[a] = max_cell[a] - min_cell[a] + 1;
      cells = extent_[a] <= kDenseCellsPerEntry * listings ? cells * extent_[a] : 0;
      if (cells > kDenseCellsPerEntry * listings) cells = 0;
    }
    if (cells > 0)
      build_dense(hi, cells);
    else
      build_hashed(hi, listings);
  }

  bool is_large(const Box& b) const {
    return cell_count(cell_of(b.lo), cell_of(b.hi)) > kMaxCells;
  }
  const std::vector<int>& large() const {
    return large_;
  }

  /// The cell holding point x.
  Cell cell_of(const Vec3& x) const {
    return {index(x.x()), index(x.y()), index(x.z())};
  }
  /// The cell holding box b's lower corner.
  const Cell& lower_cell(int b) const {
    return lo_[b];
  }

  /// Calls visit(cell) for every cell the box overlaps.
  template <class Visit>
  void for_each_cell(const Box& b, Visit visit) const {
    for_each_cell_of(cell_of(b.lo), cell_of(b.hi), visit);
  }

  /// Calls visit(box) for every small box listed in `cell`, in increasing box order.
  template <class Visit>
  void for_each_in_cell(const Cell& cell, Visit visit) const {
    if (!dense_start_.empty()) {
      const long slot = dense_slot(cell);
      if (slot < 0) return;
      for (long k = dense_start_[slot]; k < dense_start_[slot + 1]; ++k) visit(dense_boxes_[k]);
      return;
    }
    const Key key = hash(cell);
    auto it = std::lower_bound(hashed_.begin(), hashed_.end(), Entry{key, -1});
    for (; it != hashed_.end() && it->key == key; ++it) visit(it->box);
  }

 private:
  using Key = std::uint64_t;
  struct Entry {
    Key key;
    int box;
    bool operator<(const Entry& o) const { return key != o.key ? key < o.key : box < o.box; }
  };
  static constexpr long kNoCell = std::numeric_limits<long>::max() / 4;

  /// Cell index along an axis, clamped so that huge coordinates cannot overflow the cast.
  long index(double x) const {
    return static_cast<long>(std::clamp(std::floor(x * inverse_cell_), -1e15, 1e15));
  }

  static long cell_count(const Cell& lo, const Cell& hi) {
    long count = 1;
    for (int a = 0; a < 3; ++a) {
      count *= hi[a] - lo[a] + 1;
      if (count > kMaxCells) return kMaxCells + 1;
    }
    return count;
  }

  template <class Visit>
  static void for_each_cell_of(const Cell& lo, const Cell& hi, Visit visit) {
    for (long i = lo[0]; i <= hi[0]; ++i)
      for (long j = lo[1]; j <= hi[1]; ++j)
        for (long k = lo[2]; k <= hi[2]; ++k) visit(Cell{i, j, k});
  }

  bool is_small(int b) const {
    return !std::binary_search(large_.begin(), large_.end(), b);
  }

  /// Row-major slot of a cell in the dense region, or −1 outside it.
  long dense_slot(const Cell& c) const {
    long slot = 0;
    for (int a = 0; a < 3; ++a) {
      const long d = c[a] - origin_[a];
      if (d < 0 || d >= extent_[a]) return -1;
      slot = slot * extent_[a] + d;
    }
    return slot;
  }

  /// Counting sort of the small boxes into their cells (box order kept within a cell).
  void build_dense(const std::vector<Cell>& hi, long cells) {
    const int n = static_cast<int>(lo_.size());
    dense_start_.assign(cells + 1, 0);
    for (int b = 0; b < n; ++b)
      if (is_small(b))
        for_each_cell_of(lo_[b], hi[b], [&](const Cell& c) { ++dense_start_[dense_slot(c) + 1]; });
    for (long c = 0; c < cells; ++c) dense_start_[c + 1] += dense_start_[c];
    dense_boxes_.resize(dense_start_[cells]);
    std::vector<long> cursor(dense_start_.begin(), dense_start_.end() - 1);
    for (int b = 0; b < n; ++b)
      if (is_small(b))
        for_each_cell_of(lo_[b], hi[b],
                         [&](const Cell& c) { dense_boxes_[cursor[dense_slot(c)]++] = b; });
  }

  /// 21 bits per axis; distant cells that wrap onto one key only cost extra box tests.
  static Key hash(const Cell& c) {
    constexpr long mask = (1L << 21) - 1;
    return (static_cast<Key>(c[0] & mask) << 42) | (static_cast<Key>(c[1] & mask) << 21) |
           static_cast<Key>(c[2] & mask);
  }

  void build_hashed(const std::vector<Cell>& hi, long listings) {
    const int n = static_cast<int>(lo_.size());
    hashed_.reserve(listings);
    for (int b = 0; b < n; ++b)
      if (is_small(b))
        for_each_cell_of(lo_[b], hi[b], [&](const Cell& c) { hashed_.push_back({hash(c), b}); });
    std::sort(hashed_.begin(), hashed_.end());
  }

  double inverse_cell_;
  std::vector<Cell> lo_;  ///< lower cell of every box
  std::vector<int> large_;
  Cell origin_{}, extent_{};
  std::vector<long> dense_start_;  ///< CSR offsets per dense slot
  std::vector<int> dense_boxes_;
  std::vector<Entry> hashed_;
};

/// Every (query, target) whose boxes overlap and that `accept` keeps, sorted. A pair of small
/// boxes is reported from exactly one cell, the one holding the lower corner of their overlap
/// (the larger lower cell of the two, per axis); a large box is tested against every box of
/// the other set. `accept` is asked first: it is cheaper than the box test.
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
        if (accept(q, t) && overlap(box, targets[t])) local.push_back({q, t});
      };
      if (grid.is_large(box)) {
        for (int t = 0; t < static_cast<int>(targets.size()); ++t) consider(t);
        continue;
      }
      for (int t : grid.large()) consider(t);
      const Cell query_lo = grid.cell_of(box.lo);
      grid.for_each_cell(box, [&](const Cell& c) {
        grid.for_each_in_cell(c, [&](int t) {
          const Cell& target_lo = grid.lower_cell(t);
          for (int a = 0; a < 3; ++a)
            if (std::max(query_lo[a], target_lo[a]) != c[a]) return;  // reported elsewhere
          consider(t);
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
