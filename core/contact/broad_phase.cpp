#include "contact/broad_phase.hpp"

#include <algorithm>
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

/// Targets sorted by their lower bound along one axis, for range queries.
struct SortedTargets {
  std::vector<int> order;
  std::vector<double> lo;
  double max_width = 0.0;

  SortedTargets(const std::vector<Box>& targets, int axis) : order(targets.size()) {
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return targets[a].lo[axis] < targets[b].lo[axis]; });
    lo.reserve(order.size());
    for (int t : order) {
      lo.push_back(targets[t].lo[axis]);
      max_width = std::max(max_width, targets[t].hi[axis] - targets[t].lo[axis]);
    }
  }
};

/// Every (query, target) whose boxes overlap and that `accept` keeps, sorted.
template <class Accept>
std::vector<std::array<int, 2>> sweep(const std::vector<Box>& queries,
                                      const std::vector<Box>& targets, int axis, Accept accept) {
  const SortedTargets sorted(targets, axis);
  std::vector<std::array<int, 2>> pairs;
  const int n = static_cast<int>(queries.size());
#pragma omp parallel if (n >= kMinParallelItems)
  {
    std::vector<std::array<int, 2>> local;
#pragma omp for schedule(dynamic, 256) nowait
    for (int q = 0; q < n; ++q) {
      const Box& box = queries[q];
      auto k =
          std::lower_bound(sorted.lo.begin(), sorted.lo.end(), box.lo[axis] - sorted.max_width) -
          sorted.lo.begin();
      for (; k < static_cast<long>(sorted.lo.size()) && sorted.lo[k] <= box.hi[axis]; ++k) {
        const int t = sorted.order[k];
        if (overlap(box, targets[t]) && accept(q, t)) local.push_back({q, t});
      }
    }
#pragma omp critical
    pairs.insert(pairs.end(), local.begin(), local.end());
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// The axis along which the primitives' centres spread most (fewest overlaps to scan).
int sweep_axis(const Positions& p) {
  if (p.rows() == 0) return 0;
  const Vec3 extent = (p.colwise().maxCoeff() - p.colwise().minCoeff()).transpose();
  int axis = 0;
  extent.maxCoeff(&axis);
  return axis;
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
  const int axis = sweep_axis(p0);
  out.vertex_face = sweep(vertex_boxes, face_boxes, axis, [&](int v, int f) {
    const auto face = mesh.faces.row(f);
    if (face[0] == v || face[1] == v || face[2] == v) return false;
    return !(mesh.is_obstacle(v) && mesh.is_obstacle(face[0]));
  });
  out.edge_edge = sweep(edge_boxes, edge_boxes, axis, [&](int a, int b) {
    if (b <= a) return false;
    const auto& ea = mesh.edges[a];
    const auto& eb = mesh.edges[b];
    if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) return false;
    return !(mesh.is_obstacle(ea[0]) && mesh.is_obstacle(eb[0]));
  });
}

}  // namespace progsim
