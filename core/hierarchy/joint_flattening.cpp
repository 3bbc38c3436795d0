#include "hierarchy/joint_flattening.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <string>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace progsim {
namespace {

using Face = std::array<int, 3>;

/// A uv triangle counts as positively oriented above this fraction of the polygon area.
constexpr double kMinRelativeArea = 1e-12;

/// Throws Error(invalid_argument) unless every face corner and both endpoints index `points`.
void check_indices(const CollapsePatch& patch) {
  const int n = static_cast<int>(patch.points.size());
  auto bad = [n](int v) { return v < 0 || v >= n; };
  bool out_of_range = bad(patch.a) || bad(patch.b);
  for (const auto* faces : {&patch.before, &patch.after})
    for (const Face& f : *faces)
      out_of_range = out_of_range || std::any_of(f.begin(), f.end(), bad);
  if (out_of_range)
    fail(Status::invalid_argument,
         "flatten_collapse: a vertex id is outside the " + std::to_string(n) + " patch points");
}

/// The boundary of `faces` (directed edges whose reverse is in no face) as one cycle of vertex
/// ids in face orientation, or nullopt if those edges do not chain into a single simple cycle.
std::optional<std::vector<int>> boundary_loop(const std::vector<Face>& faces) {
  std::set<std::pair<int, int>> edges;
  for (const Face& f : faces)
    for (int k = 0; k < 3; ++k) edges.insert({f[k], f[(k + 1) % 3]});
  std::map<int, int> next;
  for (const Face& f : faces)
    for (int k = 0; k < 3; ++k)
      if (edges.count({f[(k + 1) % 3], f[k]}) == 0 && !next.emplace(f[k], f[(k + 1) % 3]).second)
        return std::nullopt;  // two boundary edges leave one vertex
  if (next.size() < 3) return std::nullopt;
  std::vector<int> loop;
  int v = next.begin()->first;
  do {
    loop.push_back(v);
    const auto it = next.find(v);
    if (it == next.end() || loop.size() > next.size()) return std::nullopt;
    v = it->second;
  } while (v != loop.front());
  if (loop.size() != next.size()) return std::nullopt;
  return loop;
}

/// `loop` with b renamed a and repeats of a dropped: the boundary the after faces must have.
std::vector<int> merged_loop(const std::vector<int>& loop, int a, int b) {
  std::vector<int> merged;
  for (int v : loop)
    if (merged.empty() || merged.back() != (v == b ? a : v)) merged.push_back(v == b ? a : v);
  if (merged.size() > 1 && merged.back() == merged.front()) merged.pop_back();
  return merged;
}

/// Whether two vertex cycles are equal up to rotation (same direction).
bool same_cycle(const std::vector<int>& x, std::vector<int> y) {
  const auto start = std::find(y.begin(), y.end(), x.empty() ? -1 : x.front());
  if (x.size() != y.size() || start == y.end()) return false;
  std::rotate(y.begin(), start, y.end());
  return x == y;
}

/// Moves loop vertex `skip` (if on the loop) onto the chord between its loop neighbours at its
/// 3D length ratio, so that removing it from the loop keeps the polygon.
void place_on_chord(const std::vector<Vec3>& x, const std::vector<int>& loop, int skip,
                    std::vector<Vec2>& uv) {
  const auto at = std::find(loop.begin(), loop.end(), skip);
  if (at == loop.end()) return;
  const std::size_t k = at - loop.begin(), n = loop.size();
  const int prev = loop[(k + n - 1) % n], next = loop[(k + 1) % n];
  const double to_prev = (x[skip] - x[prev]).norm(), to_next = (x[next] - x[skip]).norm();
  uv[skip] = (to_next * uv[prev] + to_prev * uv[next]) / (to_prev + to_next);
}

/// Puts the loop vertices on the unit circle, CCW at angles proportional to 3D arclength (the
/// convex boundary of Floater 2003). A loop vertex `skip` (b, when a and b both lie on the loop)
/// is left out of the arclength and put on the chord between its loop neighbours at its 3D
/// length ratio.
void place_boundary(const std::vector<Vec3>& x, const std::vector<int>& loop, int skip,
                    std::vector<Vec2>& uv) {
  std::vector<int> ring;
  std::copy_if(loop.begin(), loop.end(), std::back_inserter(ring),
               [skip](int v) { return v != skip; });
  std::vector<double> arclength{0.0};
  for (std::size_t k = 0; k < ring.size(); ++k)
    arclength.push_back(arclength.back() + (x[ring[(k + 1) % ring.size()]] - x[ring[k]]).norm());
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const double angle = kTwoPi * arclength[k] / arclength.back();
    uv[ring[k]] = Vec2(std::cos(angle), std::sin(angle));
  }
  place_on_chord(x, loop, skip, uv);
}

/// The projection (2 × 3) onto the plane normal to the patch's area-weighted normal: nearly
/// isometric on the gently curved patches decimation collapses, so tracked points move little
/// (the role of the conformal joint flattening of Liu et al. 2021).
Eigen::Matrix<double, 2, 3> patch_projection(const CollapsePatch& patch) {
  Vec3 normal = Vec3::Zero();
  for (const Face& f : patch.before) {
    const Vec3& x0 = patch.points[f[0]];
    normal += (patch.points[f[1]] - x0).cross(patch.points[f[2]] - x0);
  }
  Eigen::Matrix<double, 2, 3> projection;
  projection.row(0) = normal.unitOrthogonal().transpose();
  projection.row(1) = normal.normalized().cross(projection.row(0).transpose()).transpose();
  return projection;
}

/// The projected flattening: every point projected, b on the chord of its loop neighbours when
/// both a and b are on the loop; the merged vertex takes the uv of a or b when one is on the
/// loop (the polygon must not change), else merged_point's projection.
JointFlattening projected_flattening(const CollapsePatch& patch, const std::vector<int>& loop,
                                     const std::vector<bool>& on_loop, int skip) {
  const Eigen::Matrix<double, 2, 3> projection = patch_projection(patch);
  JointFlattening flat;
  flat.kind = FlatteningKind::projected;
  for (const Vec3& x : patch.points) flat.uv.push_back(projection * x);
  place_on_chord(patch.points, loop, skip, flat.uv);
  flat.merged_uv = on_loop[patch.a]   ? flat.uv[patch.a]
                   : on_loop[patch.b] ? flat.uv[patch.b]
                                      : Vec2(projection * patch.merged_point);
  return flat;
}

/// Mean-value weights (Floater 2003) of vertex i, placed at 3D position `center`, over its
/// neighbours in `faces`: w_j = (tan(α/2) + tan(β/2)) / |x_j − center|, α and β the corner angles
/// at i on either side of edge ij. (x.size()), zero for non-neighbours.
std::vector<double> mean_value_weights(int i, const Vec3& center, const std::vector<Face>& faces,
                                       const std::vector<Vec3>& x) {
  std::vector<double> w(x.size(), 0.0);
  for (const Face& f : faces)
    for (int k = 0; k < 3; ++k) {
      if (f[k] != i) continue;
      const int j = f[(k + 1) % 3], l = f[(k + 2) % 3];
      const Vec3 e_j = x[j] - center, e_l = x[l] - center;
      // tan(θ/2) = sin θ / (1 + cos θ), θ the angle between e_j and e_l
      const double tan_half = e_j.cross(e_l).norm() / (e_j.norm() * e_l.norm() + e_j.dot(e_l));
      w[j] += tan_half / e_j.norm();
      w[l] += tan_half / e_l.norm();
    }
  return w;
}

/// Solves for the uv of every vertex not on the loop as the mean-value average of its
/// neighbours in the before faces (Floater 2003), one dense system. False if such a vertex has
/// no neighbours.
bool solve_interior(const CollapsePatch& patch, const std::vector<bool>& on_loop,
                    std::vector<Vec2>& uv) {
  std::vector<int> unknown, slot(patch.points.size(), -1);
  for (std::size_t i = 0; i < on_loop.size(); ++i)
    if (!on_loop[i]) {
      slot[i] = static_cast<int>(unknown.size());
      unknown.push_back(static_cast<int>(i));
    }
  const Eigen::Index m = static_cast<Eigen::Index>(unknown.size());
  if (m == 0) return true;
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(m, m);
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(m, 2);
  for (Eigen::Index r = 0; r < m; ++r) {
    const int i = unknown[r];
    const auto w = mean_value_weights(i, patch.points[i], patch.before, patch.points);
    for (std::size_t j = 0; j < w.size(); ++j) {
      system(r, r) += w[j];
      if (slot[j] >= 0)
        system(r, slot[j]) -= w[j];
      else
        rhs.row(r) += w[j] * uv[j].transpose();
    }
  }
  if (!(system.diagonal().minCoeff() > 0.0)) return false;
  const Eigen::MatrixX2d solution = system.partialPivLu().solve(rhs);
  for (Eigen::Index r = 0; r < m; ++r) uv[unknown[r]] = solution.row(r).transpose();
  return true;
}

/// uv of the merged vertex: that of a or b if on the loop, else the mean-value average of its
/// after-face neighbours with angles measured at merged_point.
Vec2 merged_uv(const CollapsePatch& patch, const std::vector<bool>& on_loop,
               const std::vector<Vec2>& uv) {
  if (on_loop[patch.a]) return uv[patch.a];
  if (on_loop[patch.b]) return uv[patch.b];
  const auto w = mean_value_weights(patch.a, patch.merged_point, patch.after, patch.points);
  Vec2 sum = Vec2::Zero();
  for (std::size_t j = 0; j < w.size(); ++j) sum += w[j] * uv[j];
  return sum / std::accumulate(w.begin(), w.end(), 0.0);
}

/// Signed area of the uv triangle (p, q, r), positive when CCW.
double signed_area(const Vec2& p, const Vec2& q, const Vec2& r) {
  const Vec2 e1 = q - p, e2 = r - p;
  return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
}

/// The uv corners (3) of a before (after = false) or after face.
std::array<Vec2, 3> corner_uv(const CollapsePatch& patch, const JointFlattening& flat,
                              const Face& f, bool after) {
  std::array<Vec2, 3> corners;
  for (int k = 0; k < 3; ++k)
    corners[k] = after && f[k] == patch.a ? flat.merged_uv : flat.uv[f[k]];
  return corners;
}

/// Whether the uv angles of `faces` around interior vertex v sum to one turn (2π): positive
/// triangles can also wind around a vertex twice.
bool winds_once(const CollapsePatch& patch, const JointFlattening& flat,
                const std::vector<Face>& faces, bool after, int v) {
  double turn = 0.0;
  for (const Face& f : faces)
    for (int k = 0; k < 3; ++k)
      if (f[k] == v) {
        const auto c = corner_uv(patch, flat, f, after);
        const Vec2 e1 = c[(k + 1) % 3] - c[k], e2 = c[(k + 2) % 3] - c[k];
        turn += std::atan2(e1.x() * e2.y() - e1.y() * e2.x(), e1.dot(e2));
      }
  return std::abs(turn - kTwoPi) < 1e-6;
}

/// Whether point r, collinear with segment pq, lies on it.
bool on_segment(const Vec2& p, const Vec2& q, const Vec2& r) {
  return (r - p).dot(r - q) <= 0.0;
}

/// Whether the closed segments pq and rt share a point (orientation tests with the collinear
/// cases handled).
bool segments_meet(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& t) {
  const double o1 = signed_area(p, q, r), o2 = signed_area(p, q, t);
  const double o3 = signed_area(r, t, p), o4 = signed_area(r, t, q);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return (o1 == 0 && on_segment(p, q, r)) || (o2 == 0 && on_segment(p, q, t)) ||
         (o3 == 0 && on_segment(r, t, p)) || (o4 == 0 && on_segment(r, t, q));
}

/// Whether the uv boundary polygon is simple: no two non-adjacent sides cross or touch.
bool is_simple(const std::vector<Vec2>& uv, const std::vector<int>& loop) {
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the wrap-around
      if (segments_meet(uv[loop[i]], uv[loop[(i + 1) % n]], uv[loop[j]], uv[loop[(j + 1) % n]]))
        return false;
    }
  return true;
}

/// Whether the boundary polygon of the after faces is simple (it differs from the before
/// polygon when a border corner at b is cut off).
bool after_loop_is_simple(const CollapsePatch& patch, const JointFlattening& flat,
                          const std::vector<int>& loop) {
  std::vector<int> after = merged_loop(loop, patch.a, patch.b);
  std::vector<Vec2> uv = flat.uv;
  uv[patch.a] = flat.merged_uv;
  return is_simple(uv, after);
}

/// Every uv finite, every before and after uv triangle above kMinRelativeArea × the polygon
/// area, the polygon simple and the interior vertices wound once: the piecewise-linear maps
/// of both patches onto the polygon are then bijective.
bool is_valid(const CollapsePatch& patch, const JointFlattening& flat, const std::vector<int>& loop,
              const std::vector<bool>& on_loop) {
  double polygon = 0.0;
  for (std::size_t k = 0; k < loop.size(); ++k)
    polygon += signed_area(Vec2::Zero(), flat.uv[loop[k]], flat.uv[loop[(k + 1) % loop.size()]]);
  bool valid = flat.merged_uv.allFinite() && std::isfinite(polygon);
  for (const Vec2& p : flat.uv) valid = valid && p.allFinite();
  for (bool after : {false, true})
    for (const Face& f : after ? patch.after : patch.before) {
      const auto c = corner_uv(patch, flat, f, after);
      valid = valid && signed_area(c[0], c[1], c[2]) > kMinRelativeArea * polygon;
    }
  if (!valid || !is_simple(flat.uv, loop) || !after_loop_is_simple(patch, flat, loop)) return false;
  for (std::size_t v = 0; v < on_loop.size(); ++v)
    if (!on_loop[v] && !winds_once(patch, flat, patch.before, false, static_cast<int>(v)))
      return false;
  return on_loop[patch.a] || on_loop[patch.b] ||
         winds_once(patch, flat, patch.after, true, patch.a);
}

/// The convex flattening (Floater 2003); empty uv if an interior vertex has no neighbours.
JointFlattening convex_flattening(const CollapsePatch& patch, const std::vector<int>& loop,
                                  const std::vector<bool>& on_loop, int skip) {
  JointFlattening flat;
  flat.kind = FlatteningKind::convex;
  flat.uv.assign(patch.points.size(), Vec2::Zero());
  place_boundary(patch.points, loop, skip, flat.uv);
  if (!solve_interior(patch, on_loop, flat.uv)) return {};
  flat.merged_uv = merged_uv(patch, on_loop, flat.uv);
  return flat;
}

/// Barycentric weights (3) of p in the uv triangle c.
Vec3 barycentric(const Vec2& p, const std::array<Vec2, 3>& c) {
  return Vec3(signed_area(p, c[1], c[2]), signed_area(c[0], p, c[2]), signed_area(c[0], c[1], p)) /
         signed_area(c[0], c[1], c[2]);
}

}  // namespace

std::optional<JointFlattening> flatten_collapse(const CollapsePatch& patch) {
  if (auto flat = flatten_collapse(patch, FlatteningKind::projected)) return flat;
  return flatten_collapse(patch, FlatteningKind::convex);
}

std::optional<JointFlattening> flatten_collapse(const CollapsePatch& patch, FlatteningKind kind) {
  check_indices(patch);
  const auto loop = boundary_loop(patch.before), after_loop = boundary_loop(patch.after);
  if (!loop || !after_loop) return std::nullopt;
  std::vector<bool> on_loop(patch.points.size(), false);
  for (int v : *loop) on_loop[v] = true;
  const int chord = on_loop[patch.a] && on_loop[patch.b] ? patch.b : -1;
  // b on the chord keeps the polygon; b left in place cuts its border corner off.
  for (int skip : {chord, -1}) {
    if (!same_cycle(merged_loop(*loop, patch.a, patch.b), *after_loop)) break;
    JointFlattening flat = kind == FlatteningKind::projected
                               ? projected_flattening(patch, *loop, on_loop, skip)
                               : convex_flattening(patch, *loop, on_loop, skip);
    if (flat.uv.size() == patch.points.size() && is_valid(patch, flat, *loop, on_loop)) return flat;
    if (skip < 0 || kind == FlatteningKind::convex) break;
  }
  return std::nullopt;
}

std::pair<int, Vec3> relocate_point(const CollapsePatch& patch, const JointFlattening& flat,
                                    int before_face, const Vec3& w) {
  if (before_face < 0 || before_face >= static_cast<int>(patch.before.size()) ||
      flat.uv.size() != patch.points.size())
    fail(Status::invalid_argument, "relocate_point: before face " + std::to_string(before_face) +
                                       " or the flattening does not match the patch");
  const auto c = corner_uv(patch, flat, patch.before[before_face], false);
  const Vec2 p = w[0] * c[0] + w[1] * c[1] + w[2] * c[2];
  int best = -1;
  Vec3 best_weights = Vec3::Zero();
  double best_smallest = -std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < patch.after.size(); ++j) {
    const Vec3 weights = barycentric(p, corner_uv(patch, flat, patch.after[j], true));
    if (weights.minCoeff() > best_smallest) {
      best = static_cast<int>(j);
      best_weights = weights;
      best_smallest = weights.minCoeff();
    }
  }
  if (best < 0) fail(Status::invalid_argument, "relocate_point: no usable after face");
  best_weights = best_weights.cwiseMax(0.0);
  return {best, best_weights / best_weights.sum()};
}

}  // namespace progsim
