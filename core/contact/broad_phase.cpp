#include "contact/broad_phase.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>

#include "common/error.hpp"
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
#pragma omp parallel for schedule(static) num_threads(loop_threads(count))
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
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
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
      build_dense(hi, count, cells);
    else
      build_hashed(hi, count, listings);
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

  /// Cells in the block lo..hi, capped at kMaxCells + 1 (more: a large box).
  static long cell_count(const Cell& lo, const Cell& hi) {
    long count = 1;
    for (int a = 0; a < 3; ++a) {
      count *= hi[a] - lo[a] + 1;
      if (count > kMaxCells) return kMaxCells + 1;
    }
    return count;
  }

  /// Calls visit(cell) for every cell of the block lo..hi.
  template <class Visit>
  static void for_each_cell_of(const Cell& lo, const Cell& hi, Visit visit) {
    for (long i = lo[0]; i <= hi[0]; ++i)
      for (long j = lo[1]; j <= hi[1]; ++j)
        for (long k = lo[2]; k <= hi[2]; ++k) visit(Cell{i, j, k});
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
  /// count[b + 1]: cells of box b (the constructor's); boxes over kMaxCells are large.
  void build_dense(const std::vector<Cell>& hi, const std::vector<long>& count, long cells) {
    const int n = static_cast<int>(lo_.size());
    dense_start_.assign(cells + 1, 0);
    for (int b = 0; b < n; ++b)
      if (count[b + 1] <= kMaxCells)
        for_each_cell_of(lo_[b], hi[b], [&](const Cell& c) { ++dense_start_[dense_slot(c) + 1]; });
    for (long c = 0; c < cells; ++c) dense_start_[c + 1] += dense_start_[c];
    dense_boxes_.resize(dense_start_[cells]);
    std::vector<long> cursor(dense_start_.begin(), dense_start_.end() - 1);
    for (int b = 0; b < n; ++b)
      if (count[b + 1] <= kMaxCells)
        for_each_cell_of(lo_[b], hi[b],
                         [&](const Cell& c) { dense_boxes_[cursor[dense_slot(c)]++] = b; });
  }

  /// 21 bits per axis; distant cells that wrap onto one key only cost extra box tests.
  static Key hash(const Cell& c) {
    constexpr long mask = (1L << 21) - 1;
    return (static_cast<Key>(c[0] & mask) << 42) | (static_cast<Key>(c[1] & mask) << 21) |
           static_cast<Key>(c[2] & mask);
  }

  void build_hashed(const std::vector<Cell>& hi, const std::vector<long>& count, long listings) {
    const int n = static_cast<int>(lo_.size());
    hashed_.reserve(listings);
    for (int b = 0; b < n; ++b)
      if (count[b + 1] <= kMaxCells)
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

/// Every (query, target) of the listed boxes whose boxes overlap and that `accept` keeps, as
/// indices into `queries` and `targets`, in the order of `query_ids` and, per query, of target
/// (so sorted when `query_ids` ascend). A pair of small boxes is reported from
/// exactly one cell, the one holding the lower corner of their overlap (the larger lower cell
/// of the two, per axis); a large box is tested against every listed box of the other set.
/// `accept` is asked first: it is cheaper than the box test.
template <class Accept>
std::vector<std::array<int, 2>> overlapping_pairs(const std::vector<Box>& queries,
                                                  const std::vector<int>& query_ids,
                                                  const std::vector<Box>& targets,
                                                  const std::vector<int>& target_ids, double cell,
                                                  Accept accept) {
  std::vector<Box> listed(target_ids.size());
  for (std::size_t k = 0; k < target_ids.size(); ++k) listed[k] = targets[target_ids[k]];
  const BoxGrid grid(listed, cell);
  const int n = static_cast<int>(query_ids.size());
  const int threads = loop_threads(n);
  // Contiguous blocks of queries in thread order, joined in that order: no global sort.
  std::vector<std::vector<std::array<int, 2>>> per_thread(threads);
#pragma omp parallel num_threads(threads)
  {
    std::vector<std::array<int, 2>>& local = per_thread[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      const std::size_t first = local.size();
      const int q = query_ids[i];
      const Box& box = queries[q];
      auto consider = [&](int k) {
        const int t = target_ids[k];
        if (accept(q, t) && overlap(box, listed[k])) local.push_back({q, t});
      };
      const Cell query_lo = grid.cell_of(box.lo), query_hi = grid.cell_of(box.hi);
      if (BoxGrid::cell_count(query_lo, query_hi) > BoxGrid::kMaxCells) {
        for (int k = 0; k < static_cast<int>(listed.size()); ++k) consider(k);
      } else {
        for (int k : grid.large()) consider(k);
        BoxGrid::for_each_cell_of(query_lo, query_hi, [&](const Cell& c) {
          grid.for_each_in_cell(c, [&](int k) {
            const Cell& target_lo = grid.lower_cell(k);
            for (int a = 0; a < 3; ++a)
              if (std::max(query_lo[a], target_lo[a]) != c[a]) return;  // reported elsewhere
            consider(k);
          });
        });
      }
      std::sort(local.begin() + static_cast<std::ptrdiff_t>(first), local.end());
    }
  }
  std::vector<std::array<int, 2>> pairs;
  std::size_t total = 0;
  for (const auto& local : per_thread) total += local.size();
  pairs.reserve(total);
  for (const auto& local : per_thread) pairs.insert(pairs.end(), local.begin(), local.end());
  return pairs;
}

/// 0, 1, …, n − 1.
std::vector<int> all_indices(int n) {
  std::vector<int> out(n);
  std::iota(out.begin(), out.end(), 0);
  return out;
}

/// The indices whose flag is set (`set`) or clear (`!set`); any non-zero flag is set.
std::vector<int> indices_where(const std::vector<char>& flags, bool set) {
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(flags.size()); ++i)
    if ((flags[i] != 0) == set) out.push_back(i);
  return out;
}

/// Per primitive of K vertices: whether any of its vertices moves.
template <int K, class IndexOf>
std::vector<char> primitives_moving(int count, IndexOf index_of, const std::vector<char>& moving) {
  std::vector<char> out(count, 0);
  for (int i = 0; i < count; ++i)
    for (int k = 0; k < K; ++k) out[i] = out[i] || moving[index_of(i)[k]];
  return out;
}

/// The contact points (CollisionMesh::points) whose flag is `value`.
std::vector<int> points_where(const CollisionMesh& mesh, const std::vector<char>& flags,
                              bool value) {
  std::vector<int> out;
  for (int v : mesh.points)
    if (static_cast<bool>(flags[v]) == value) out.push_back(v);
  return out;
}

/// Grid cell size: the mean largest extent of the boxes (at least the inflation).
double cell_size(const std::vector<Box>& boxes, double inflation) {
  double sum = 0.0;
  for (const Box& b : boxes) sum += (b.hi - b.lo).maxCoeff();
  return std::max(boxes.empty() ? 1.0 : sum / static_cast<double>(boxes.size()), inflation);
}

}  // namespace

void find_candidates(const CollisionMesh& mesh, const Positions& p0, const Positions& p1,
                     double inflation, CandidateSet& out, const std::vector<char>* moving) {
  const double r = 0.5 * inflation;  // two boxes grown by r overlap iff gap ≤ 2r per axis
  const int nv = mesh.num_vertices();
  const int nf = static_cast<int>(mesh.faces.rows());
  const int ne = static_cast<int>(mesh.edges.size());
  if (moving && static_cast<int>(moving->size()) != nv)
    fail(Status::invalid_argument, "find_candidates: " + std::to_string(moving->size()) +
                                       " moving flags for " + std::to_string(nv) + " vertices");
  const std::vector<int> vertex_ids = all_indices(nv);
  const auto vertex_of = [&](int v) { return &vertex_ids[v]; };
  const auto face_of = [&](int f) { return mesh.faces.row(f).data(); };
  const auto edge_of = [&](int e) { return mesh.edges[e].data(); };
  const auto vertex_boxes = boxes<1>(nv, vertex_of, p0, p1, r);
  const auto face_boxes = boxes<3>(nf, face_of, p0, p1, r);
  const auto edge_boxes = boxes<2>(ne, edge_of, p0, p1, r);
  const double cell = cell_size(edge_boxes, inflation);
  const auto vertex_face = [&](int v, int f) {
    const auto face = mesh.faces.row(f);
    if (face[0] == v || face[1] == v || face[2] == v) return false;
    return !(mesh.is_obstacle(v) && mesh.is_obstacle(face[0]));
  };
  const auto edge_edge = [&](int a, int b) {
    const auto& ea = mesh.edges[a];
    const auto& eb = mesh.edges[b];
    if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) return false;
    return !(mesh.is_obstacle(ea[0]) && mesh.is_obstacle(eb[0]));
  };
  if (!moving) {
    const std::vector<int> edges = all_indices(ne);
    out.vertex_face = overlapping_pairs(vertex_boxes, mesh.points, face_boxes, all_indices(nf),
                                        cell, vertex_face);
    out.edge_edge = overlapping_pairs(edge_boxes, edges, edge_boxes, edges, cell,
                                      [&](int a, int b) { return a < b && edge_edge(a, b); });
  } else {
    // Pairs with a moving vertex: moving vertices against every face and the others against
    // the moving faces; moving edges against every edge, a pair of two moving edges once.
    const std::vector<char> face_moves = primitives_moving<3>(nf, face_of, *moving);
    const std::vector<char> edge_moves = primitives_moving<2>(ne, edge_of, *moving);
    out.vertex_face = overlapping_pairs(vertex_boxes, points_where(mesh, *moving, true), face_boxes,
                                        all_indices(nf), cell, vertex_face);
    const auto still_vertex_moving_face =
        overlapping_pairs(vertex_boxes, points_where(mesh, *moving, false), face_boxes,
                          indices_where(face_moves, true), cell, vertex_face);
    out.vertex_face.insert(out.vertex_face.end(), still_vertex_moving_face.begin(),
                           still_vertex_moving_face.end());
    out.edge_edge = overlapping_pairs(
        edge_boxes, indices_where(edge_moves, true), edge_boxes, all_indices(ne), cell,
        [&](int a, int b) { return (!edge_moves[b] || a < b) && edge_edge(a, b); });
    for (auto& pair : out.edge_edge)
      if (pair[1] < pair[0]) std::swap(pair[0], pair[1]);
    std::sort(out.vertex_face.begin(), out.vertex_face.end());  // two lists joined
    std::sort(out.edge_edge.begin(), out.edge_edge.end());      // pairs swapped
  }  // without `moving`, the queries ascend: the pairs come sorted
}

}  // namespace progsim
