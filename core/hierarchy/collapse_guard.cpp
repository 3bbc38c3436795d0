#include "hierarchy/collapse_guard.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <cmath>

#include "mesh/intersection_check.hpp"

namespace progsim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;

Point point(const Vec3& p) {
  return {p.x(), p.y(), p.z()};
}

Triangle triangle(const std::array<Vec3, 3>& p) {
  return {point(p[0]), point(p[1]), point(p[2])};
}

/// Position of vertex `v` in `corners`, or −1.
int slot(const std::array<int, 3>& corners, int v) {
  for (int k = 0; k < 3; ++k)
    if (corners[k] == v) return k;
  return -1;
}

/// The grid is rebuilt with larger cells once the live faces fall below this share of those at
/// the last rebuild (their mean size has grown by about 1/√share).
constexpr double kRebuildShrink = 0.5;

}  // namespace

CollapseGuard::CollapseGuard(const Positions& vertices, const Faces& faces,
                             std::vector<double> offsets)
    : positions_(vertices), offsets_(std::move(offsets)) {
  faces_.resize(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    faces_[f] = {faces(f, 0), faces(f, 1), faces(f, 2)};
  alive_.assign(faces_.size(), 1);
  stamp_.assign(faces_.size(), 0);
  seen_.assign(faces_.size(), 0);
  if (!offsets_.empty()) margin_ = 2.0 * *std::max_element(offsets_.begin(), offsets_.end());
  live_faces_ = static_cast<int>(faces_.size());
  on_crossing_.assign(vertices.rows(), 0);
  for (const FacePair& pair : intersecting_faces(vertices, faces))
    for (int f : {pair.a, pair.b})
      for (int k = 0; k < 3; ++k) on_crossing_[faces(f, k)] = 1;
  rebuild();
}

CollapseGuard::Placed CollapseGuard::placed(int face) const {
  Placed out{faces_[face], {}};
  for (int k = 0; k < 3; ++k) out.points[k] = positions_.row(out.corners[k]).transpose();
  return out;
}

std::vector<CollapseGuard::Placed> CollapseGuard::after_faces(
    int a, int b, const Vec3& merged, const std::vector<int>& around) const {
  std::vector<Placed> out;
  for (int f : around) {
    Placed face = placed(f);
    const int ka = slot(face.corners, a), kb = slot(face.corners, b);
    if (ka >= 0 && kb >= 0) continue;  // the faces on the edge vanish
    const int k = ka >= 0 ? ka : kb;
    face.corners[k] = a;
    face.points[k] = merged;
    out.push_back(face);
  }
  return out;
}

bool CollapseGuard::allows(int v0, int v1, const Vec3& merged, const std::vector<int>& around,
                           CrossingRule rule) const {
  const std::vector<Placed> after = after_faces(v0, v1, merged, around);
  std::vector<int> near;
  for (std::size_t i = 0; i < after.size(); ++i) {
    for (std::size_t j = i + 1; j < after.size(); ++j)
      if (cross(after[i], after[j]) || too_close(after[i], after[j], v0)) return false;
    candidates(box_of(after[i].points, margin_), around, near);
    for (int f : near) {
      const Placed other = placed(f);
      if (cross(after[i], other) && (rule == CrossingRule::none || !crossed_before(other, around)))
        return false;
      if (too_close(after[i], other, v0)) return false;
    }
  }
  return true;
}

bool CollapseGuard::crossed_before(const Placed& other, const std::vector<int>& around) const {
  for (int f : around)
    if (cross(placed(f), other)) return true;
  return false;
}

void CollapseGuard::collapsed(int removed, int kept, const Vec3& merged,
                              const std::vector<int>& around) {
  positions_.row(kept) = merged.transpose();
  on_crossing_[kept] = 0;  // allows() found none of its faces crossing
  if (!offsets_.empty()) offsets_[kept] = std::max(offsets_[kept], offsets_[removed]);
  for (int f : around) {
    Corners& c = faces_[f];
    const int kr = slot(c, removed);
    if (kr >= 0 && slot(c, kept) >= 0) {
      alive_[f] = 0;
      --live_faces_;
      continue;
    }
    if (kr >= 0) c[kr] = kept;
    ++stamp_[f];
    insert(f);
  }
  if (live_faces_ < kRebuildShrink * live_at_rebuild_) rebuild();
}

bool CollapseGuard::cross(const Placed& a, const Placed& b) const {
  std::array<int, 3> shared_in_a{}, shared_in_b{};
  int shared = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = slot(b.corners, a.corners[i]);
    if (j < 0) continue;
    shared_in_a[shared] = i;
    shared_in_b[shared] = j;
    ++shared;
  }
  const Triangle ta = triangle(a.points), tb = triangle(b.points);
  if (ta.is_degenerate() || tb.is_degenerate()) return true;  // never accept a flat face
  if (shared == 0) return CGAL::do_intersect(ta, tb);
  if (shared == 1) {  // beyond the shared vertex: an opposite edge meets the other face
    const int i = shared_in_a[0], j = shared_in_b[0];
    const Segment opposite_a(point(a.points[(i + 1) % 3]), point(a.points[(i + 2) % 3]));
    const Segment opposite_b(point(b.points[(j + 1) % 3]), point(b.points[(j + 2) % 3]));
    return CGAL::do_intersect(opposite_a, tb) || CGAL::do_intersect(opposite_b, ta);
  }
  if (shared == 2) {  // folded onto each other: coplanar, apexes on one side of the edge
    const int apex_a = 3 - shared_in_a[0] - shared_in_a[1];
    const int apex_b = 3 - shared_in_b[0] - shared_in_b[1];
    const Point s = point(a.points[shared_in_a[0]]), t = point(a.points[shared_in_a[1]]);
    const Point pa = point(a.points[apex_a]), pb = point(b.points[apex_b]);
    return CGAL::orientation(s, t, pa, pb) == CGAL::COPLANAR &&
           CGAL::coplanar_orientation(s, t, pa, pb) == CGAL::POSITIVE;
  }
  return true;  // the same face twice
}

double CollapseGuard::face_offset(const Corners& corners) const {
  return std::max({offsets_[corners[0]], offsets_[corners[1]], offsets_[corners[2]]});
}

bool CollapseGuard::too_close(const Placed& a, const Placed& b, int merged) const {
  if (offsets_.empty()) return false;
  // Only pairs with the merged vertex, or a face or edge of it, are new: the others (a ring
  // vertex and an unchanged face, ...) were there before the collapse, as close as they were.
  const auto vertex_face = [&](const Placed& p, const Placed& f) {
    const bool new_face = slot(f.corners, merged) >= 0;
    const Triangle tf = triangle(f.points);
    for (int k = 0; k < 3; ++k) {
      if (slot(f.corners, p.corners[k]) >= 0 || !(new_face || p.corners[k] == merged)) continue;
      const double offset = offsets_[p.corners[k]] + face_offset(f.corners);
      if (CGAL::squared_distance(point(p.points[k]), tf) <= offset * offset) return true;
    }
    return false;
  };
  if (vertex_face(a, b) || vertex_face(b, a)) return true;
  for (int i = 0; i < 3; ++i) {
    const int a0 = a.corners[i], a1 = a.corners[(i + 1) % 3];
    for (int j = 0; j < 3; ++j) {
      const int b0 = b.corners[j], b1 = b.corners[(j + 1) % 3];
      if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) continue;
      if (a0 != merged && a1 != merged && b0 != merged && b1 != merged) continue;
      const double offset =
          std::max(offsets_[a0], offsets_[a1]) + std::max(offsets_[b0], offsets_[b1]);
      const Segment sa(point(a.points[i]), point(a.points[(i + 1) % 3]));
      const Segment sb(point(b.points[j]), point(b.points[(j + 1) % 3]));
      if (CGAL::squared_distance(sa, sb) <= offset * offset) return true;
    }
  }
  return false;
}

CollapseGuard::Box CollapseGuard::box_of(const std::array<Vec3, 3>& p, double margin) const {
  const Vec3 grow = Vec3::Constant(margin);
  return {p[0].cwiseMin(p[1]).cwiseMin(p[2]) - grow, p[0].cwiseMax(p[1]).cwiseMax(p[2]) + grow};
}

Eigen::Vector3i CollapseGuard::cell_of(const Vec3& p) const {
  return (p / cell_).array().floor().cast<int>();
}

std::int64_t CollapseGuard::key(const Eigen::Vector3i& c) const {
  // Teschner et al. 2003's spatial hash; colliding cells only add candidates.
  return (static_cast<std::int64_t>(c.x()) * 73856093) ^
         (static_cast<std::int64_t>(c.y()) * 19349663) ^
         (static_cast<std::int64_t>(c.z()) * 83492791);
}

void CollapseGuard::candidates(const Box& box, const std::vector<int>& around,
                               std::vector<int>& out) const {
  out.clear();
  ++query_;
  for (int f : around) seen_[f] = query_;
  const Eigen::Vector3i lo = cell_of(box.lo), hi = cell_of(box.hi);
  for (int i = lo.x(); i <= hi.x(); ++i)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int k = lo.z(); k <= hi.z(); ++k) {
        const auto it = grid_.find(key({i, j, k}));
        if (it == grid_.end()) continue;
        for (const auto& [f, stamp] : it->second) {
          if (!alive_[f] || stamp != stamp_[f] || seen_[f] == query_) continue;
          seen_[f] = query_;
          out.push_back(f);
        }
      }
}

void CollapseGuard::insert(int face) {
  const Box box = box_of(placed(face).points, 0.0);
  const Eigen::Vector3i lo = cell_of(box.lo), hi = cell_of(box.hi);
  for (int i = lo.x(); i <= hi.x(); ++i)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int k = lo.z(); k <= hi.z(); ++k) grid_[key({i, j, k})].push_back({face, stamp_[face]});
}

void CollapseGuard::rebuild() {
  double length = 0.0;
  int edges = 0;
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    if (!alive_[f]) continue;
    const Placed p = placed(static_cast<int>(f));
    for (int k = 0; k < 3; ++k) length += (p.points[k] - p.points[(k + 1) % 3]).norm();
    edges += 3;
  }
  cell_ = std::max(margin_, edges > 0 && length > 0.0 ? length / edges : 1.0);
  grid_.clear();
  for (std::size_t f = 0; f < faces_.size(); ++f)
    if (alive_[f]) insert(static_cast<int>(f));
  live_at_rebuild_ = live_faces_;
}

}  // namespace progsim
