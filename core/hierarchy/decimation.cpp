#include "hierarchy/decimation.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Edge_collapse_visitor_base.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <optional>
#include <string>
#include <type_traits>

#include "common/error.hpp"
#include "hierarchy/collapse_guard.hpp"
#include "hierarchy/joint_flattening.hpp"

namespace progsim {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;
namespace SMS = CGAL::Surface_mesh_simplification;

// The filter and visitor rely on CGAL 5.5's call order (filter, OnCollapsing, OnCollapsed for
// one edge in a row) and boost::optional signatures; CGAL 6 changed the latter.
static_assert(CGAL_VERSION_NR >= 1050500000 && CGAL_VERSION_NR < 1060000000,
              "progsim's decimation is written against CGAL 5.5.x");

/// Edges whose endpoints have more incident edges than this in total are not collapsed: it
/// bounds the per-collapse work of the flattening (quadratic in the patch size) on fans.
constexpr int kMaxPatchValence = 128;

/// Collapses may not create triangles of quality 4√3·A / Σ ℓ² below this (1 = equilateral),
/// unless the patch already had worse ones: coarse levels stay usable as simulation meshes.
/// (A progsim choice, not in PSQ.)
constexpr double kMinTriangleQuality = 0.05;

Vec3 to_vec3(const Kernel::Point_3& p) {
  return {p.x(), p.y(), p.z()};
}

/// Vertices are added in input order, and no garbage collection runs during decimation, so a
/// Surface_mesh vertex index equals the input vertex index throughout.
SurfaceMesh to_surface_mesh(const TriangleMesh& mesh) {
  SurfaceMesh sm;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
    sm.add_vertex(Kernel::Point_3(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2)));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const auto face = sm.add_face(VertexIndex(mesh.faces(f, 0)), VertexIndex(mesh.faces(f, 1)),
                                  VertexIndex(mesh.faces(f, 2)));
    if (face == SurfaceMesh::null_face())
      fail(Status::invalid_mesh, "decimation: CGAL's Surface_mesh cannot insert face " +
                                     std::to_string(f) + " (the mesh is not an oriented manifold)");
  }
  return sm;
}

std::array<VertexIndex, 3> face_corners(const SurfaceMesh& sm, FaceIndex f) {
  std::array<VertexIndex, 3> corners;
  int k = 0;
  for (VertexIndex v : CGAL::vertices_around_face(sm.halfedge(f), sm)) corners[k++] = v;
  return corners;
}

/// Triangle quality 4√3·A / (ℓ₀² + ℓ₁² + ℓ₂²) (Bank and Smith's shape measure): 1 for
/// equilateral, 0 for degenerate.
double triangle_quality(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const double lengths =
      (p1 - p0).squaredNorm() + (p2 - p1).squaredNorm() + (p0 - p2).squaredNorm();
  return 2.0 * std::sqrt(3.0) * (p1 - p0).cross(p2 - p0).norm() / lengths;
}

/// The user's mesh as the finest level.
HierarchyLevel input_level(const TriangleMesh& mesh) {
  HierarchyLevel level;
  level.rest = mesh;
  level.input_vertex.resize(mesh.num_vertices());
  std::iota(level.input_vertex.begin(), level.input_vertex.end(), 0);
  return level;
}

/// A point of a finer level being carried down the decimation: barycentric weights of the
/// corners (input ids) of the face it lies in.
struct TrackedPoint {
  FaceIndex face;
  std::array<int, 3> corners;
  Vec3 weights;
  bool alive = true;
};

/// The collapse accepted by the filter, until the visitor has moved its points.
struct PendingCollapse {
  VertexIndex v0, v1;
  CollapsePatch patch;
  JointFlattening flat;
  std::vector<VertexIndex> vertex_of;  ///< patch local id → mesh vertex
  std::vector<FaceIndex> before_faces;
  struct Popped {
    int point, before_face;
    Vec3 weights;  ///< in the corner order of patch.before[before_face]
  };
  std::vector<Popped> popped;
};

/// Decimation state shared by the filter and the visitor (CGAL copies both, so they hold a
/// pointer to this). Points of the finest level and of the last level reached are tracked
/// through every collapse; each time a target count is reached, a level is recorded.
class Tracker {
 public:
  Tracker(SurfaceMesh& sm, CollapseGuard guard, std::vector<int> targets, std::vector<int> groups,
          HierarchyProgress progress, void* user)
      : sm_(sm),
        guard_(std::move(guard)),
        targets_(std::move(targets)),
        group_(std::move(groups)),
        progress_(progress),
        user_(user) {
    result_.input_group = group_;
    face_points_ = sm_.add_property_map<FaceIndex, std::vector<int>>("f:progsim_points").first;
    finest_vertices_ = static_cast<int>(sm_.number_of_vertices());
    last_level_points_ = add_vertex_points();
  }

  /// Filter: accepts the collapse of profile's edge to `placement` if it makes no triangle
  /// worse than kMinTriangleQuality, its joint flattening is valid, and it makes no face cross
  /// another or come within the contact offsets (CollapseGuard).
  template <class Profile>
  bool prepare(const Profile& profile, const Kernel::Point_3& placement) {
    pending_.reset();
    if (static_cast<int>(CGAL::degree(profile.v0(), sm_) + CGAL::degree(profile.v1(), sm_)) >
        kMaxPatchValence)
      return false;
    PendingCollapse pending;
    pending.v0 = profile.v0();
    pending.v1 = profile.v1();
    gather_before_faces(pending, to_vec3(placement) == to_vec3(profile.p1()));
    make_after_faces(pending, to_vec3(placement));
    if (!keeps_quality(pending.patch)) return false;
    auto flat = flatten_collapse(pending.patch);
    if (!flat) return false;
    if (!guard_.allows(static_cast<int>(pending.v0.idx()), static_cast<int>(pending.v1.idx()),
                       to_vec3(placement), face_ids(pending.before_faces)))
      return false;
    pending.flat = std::move(*flat);
    pending_ = std::move(pending);
    return true;
  }

  /// Visitor, before the collapse: takes the tracked points off the faces that disappear or
  /// change.
  template <class Profile>
  void collapsing(const Profile& profile) {
    if (!pending_ || pending_->v0 != profile.v0() || pending_->v1 != profile.v1())
      fail(Status::internal, "decimation: collapse of an edge the filter did not see");
    PendingCollapse& p = *pending_;
    for (std::size_t k = 0; k < p.before_faces.size(); ++k) {
      for (int id : face_points_[p.before_faces[k]]) {
        if (!points_[id].alive) continue;
        p.popped.push_back({id, static_cast<int>(k), weights_in(points_[id], p, k)});
      }
      face_points_[p.before_faces[k]].clear();
    }
  }

  /// Visitor, after the collapse: puts the points back on the new faces around `kept`,
  /// records the collapse, and records a level when a target count is reached.
  template <class Profile>
  void collapsed(const Profile& profile, VertexIndex kept) {
    // CGAL collapses zero-length edges without the filter (validated meshes have none).
    if (!pending_ || pending_->v0 != profile.v0() || pending_->v1 != profile.v1())
      fail(Status::internal, "decimation: collapse of an edge the filter did not see");
    PendingCollapse& p = *pending_;
    const std::vector<FaceIndex> after_faces = match_after_faces(p, kept);
    for (const auto& popped : p.popped) {
      const auto [j, weights] = relocate_point(p.patch, p.flat, popped.before_face, popped.weights);
      TrackedPoint& point = points_[popped.point];
      point.face = after_faces[j];
      point.corners = input_corners(p, p.patch.after[j], kept);
      point.weights = weights;
      face_points_[point.face].push_back(popped.point);
    }
    const VertexIndex removed = kept == profile.v0() ? profile.v1() : profile.v0();
    group_[kept.idx()] = std::max(group_[kept.idx()], group_[removed.idx()]);
    record_collapse(p, removed, kept);
    guard_.collapsed(static_cast<int>(removed.idx()), static_cast<int>(kept.idx()),
                     to_vec3(sm_.point(kept)), face_ids(p.before_faces));
    pending_.reset();
    report_progress();
    while (next_target_ < targets_.size() &&
           static_cast<int>(sm_.number_of_vertices()) <= targets_[next_target_])
      record_level();
  }

  /// Per input vertex, its current group (−1 free).
  const std::vector<int>& groups() const { return group_; }

  /// Whether vertex v lies on a face that crosses another in the input (CollapseGuard).
  bool on_input_crossing(VertexIndex v) const {
    return guard_.on_input_crossing(static_cast<int>(v.idx()));
  }

  /// For an edge on a crossing of the input, the first of `optimal`, its endpoints and its
  /// midpoint at which the collapse crosses nothing (CollapseGuard), so that decimation can
  /// take the crossing out (the quadric optimum keeps a spike through a face where it is);
  /// `optimal` for other edges or when none does.
  template <class Profile>
  typename Profile::Point crossing_free_placement(const Profile& profile,
                                                  const typename Profile::Point& optimal) const {
    if (!on_input_crossing(profile.v0()) && !on_input_crossing(profile.v1())) return optimal;
    const std::vector<int> around = face_ids(faces_around(profile.v0(), profile.v1()));
    const typename Profile::Point candidates[] = {optimal, profile.p0(), profile.p1(),
                                                  CGAL::midpoint(profile.p0(), profile.p1())};
    for (const auto& p : candidates)
      if (guard_.allows(static_cast<int>(profile.v0().idx()), static_cast<int>(profile.v1().idx()),
                        to_vec3(p), around, CollapseGuard::CrossingRule::none))
        return p;
    return optimal;
  }

  /// The hierarchy, once decimation has ended: levels coarsest first, then the input mesh.
  MeshHierarchy finish(const TriangleMesh& input) {
    if (next_target_ < targets_.size())
      fail(Status::invalid_mesh,
           "decimation: level " + std::to_string(targets_.size() - 1 - next_target_) + " (" +
               std::to_string(targets_[next_target_]) +
               " vertices asked for) cannot be reached: "
               "stopped at " +
               std::to_string(sm_.number_of_vertices()) +
               " vertices, where every further collapse would make faces cross, bring them "
               "within their contact offsets or leave the surface invalid");
    std::reverse(result_.levels.begin(), result_.levels.end());
    std::reverse(result_.to_next.begin(), result_.to_next.end());
    std::reverse(result_.to_finest.begin(), result_.to_finest.end());
    std::reverse(result_.first_collapse.begin(), result_.first_collapse.end());
    result_.levels.push_back(input_level(input));
    result_.first_collapse.push_back(0);
    return std::move(result_);
  }

 private:
  /// One tracked point per live vertex, at a corner of one of its faces.
  std::vector<int> add_vertex_points() {
    std::vector<int> ids;
    for (VertexIndex v : sm_.vertices()) {
      auto h = sm_.halfedge(v);
      if (sm_.is_border(h)) h = sm_.opposite(sm_.next(h));
      TrackedPoint point;
      point.face = sm_.face(h);
      const auto corners = face_corners(sm_, point.face);
      for (int k = 0; k < 3; ++k) {
        point.corners[k] = static_cast<int>(corners[k].idx());
        point.weights[k] = corners[k] == v ? 1.0 : 0.0;
      }
      ids.push_back(static_cast<int>(points_.size()));
      face_points_[point.face].push_back(ids.back());
      points_.push_back(point);
    }
    return ids;
  }

  static std::vector<int> face_ids(const std::vector<FaceIndex>& faces) {
    std::vector<int> ids;
    for (FaceIndex f : faces) ids.push_back(static_cast<int>(f.idx()));
    return ids;
  }

  /// The faces incident to v0 or v1, each once.
  std::vector<FaceIndex> faces_around(VertexIndex v0, VertexIndex v1) const {
    std::vector<FaceIndex> faces;
    for (VertexIndex v : {v0, v1})
      for (FaceIndex f : CGAL::faces_around_target(sm_.halfedge(v), sm_))
        if (f != SurfaceMesh::null_face() &&
            std::find(faces.begin(), faces.end(), f) == faces.end())
          faces.push_back(f);
    return faces;
  }

  int local_id(PendingCollapse& p, VertexIndex v) {
    const auto it = std::find(p.vertex_of.begin(), p.vertex_of.end(), v);
    if (it != p.vertex_of.end()) return static_cast<int>(it - p.vertex_of.begin());
    p.vertex_of.push_back(v);
    p.patch.points.push_back(to_vec3(sm_.point(v)));
    return static_cast<int>(p.vertex_of.size()) - 1;
  }

  /// The faces around v0 and v1. The patch's merged vertex `a` is v1 when the collapse puts
  /// it at v1's position (so that a flattening keeping a's uv keeps its 3D point), else v0.
  void gather_before_faces(PendingCollapse& p, bool merged_at_v1) {
    p.before_faces = faces_around(p.v0, p.v1);
    p.patch.a = local_id(p, merged_at_v1 ? p.v1 : p.v0);
    p.patch.b = local_id(p, merged_at_v1 ? p.v0 : p.v1);
    for (FaceIndex f : p.before_faces) {
      const auto corners = face_corners(sm_, f);
      p.patch.before.push_back(
          {local_id(p, corners[0]), local_id(p, corners[1]), local_id(p, corners[2])});
    }
  }

  /// The before faces without the two on the edge, with b merged into a.
  static void make_after_faces(PendingCollapse& p, const Vec3& placement) {
    const int a = p.patch.a, b = p.patch.b;
    for (const auto& face : p.patch.before) {
      const bool has_a = std::count(face.begin(), face.end(), a) > 0;
      const bool has_b = std::count(face.begin(), face.end(), b) > 0;
      if (has_a && has_b) continue;
      auto after = face;
      std::replace(after.begin(), after.end(), b, a);
      p.patch.after.push_back(after);
    }
    p.patch.merged_point = placement;
  }

  static double worst_quality(const CollapsePatch& patch,
                              const std::vector<std::array<int, 3>>& faces, bool after) {
    double worst = 1.0;
    for (const auto& face : faces) {
      std::array<Vec3, 3> p;
      for (int k = 0; k < 3; ++k)
        p[k] = after && face[k] == patch.a ? patch.merged_point : patch.points[face[k]];
      const double quality = triangle_quality(p[0], p[1], p[2]);
      if (std::isnan(quality) || quality < worst) worst = quality;  // NaN counts as worst
    }
    return worst;
  }

  static bool keeps_quality(const CollapsePatch& patch) {
    const double before = worst_quality(patch, patch.before, false);
    return worst_quality(patch, patch.after, true) >= std::min(kMinTriangleQuality, before);
  }

  /// The point's weights reordered to the corners of before face k.
  Vec3 weights_in(const TrackedPoint& point, const PendingCollapse& p, std::size_t k) const {
    Vec3 w;
    for (int j = 0; j < 3; ++j) {
      const int input = static_cast<int>(p.vertex_of[p.patch.before[k][j]].idx());
      const auto at = std::find(point.corners.begin(), point.corners.end(), input);
      if (at == point.corners.end())
        fail(Status::internal, "decimation: a tracked point lost its face corners");
      w[j] = point.weights[at - point.corners.begin()];
    }
    return w;
  }

  std::array<int, 3> input_corners(const PendingCollapse& p, const std::array<int, 3>& face,
                                   VertexIndex kept) const {
    std::array<int, 3> out;
    for (int k = 0; k < 3; ++k)
      out[k] = static_cast<int>((face[k] == p.patch.a ? kept : p.vertex_of[face[k]]).idx());
    return out;
  }

  /// The mesh face of each of patch.after, found among the faces around `kept`.
  std::vector<FaceIndex> match_after_faces(const PendingCollapse& p, VertexIndex kept) const {
    std::vector<FaceIndex> found(p.patch.after.size(), SurfaceMesh::null_face());
    std::size_t matched = 0;
    for (FaceIndex f : CGAL::faces_around_target(sm_.halfedge(kept), sm_)) {
      if (f == SurfaceMesh::null_face()) continue;
      const auto corners = face_corners(sm_, f);
      for (std::size_t j = 0; j < found.size(); ++j) {
        const auto want = input_corners(p, p.patch.after[j], kept);
        for (int r = 0; r < 3 && found[j] == SurfaceMesh::null_face(); ++r)
          if (static_cast<int>(corners[r].idx()) == want[0] &&
              static_cast<int>(corners[(r + 1) % 3].idx()) == want[1] &&
              static_cast<int>(corners[(r + 2) % 3].idx()) == want[2]) {
            found[j] = f;
            ++matched;
          }
      }
    }
    if (matched != found.size())
      fail(Status::internal, "decimation: the faces after a collapse differ from its patch");
    return found;
  }

  void record_collapse(const PendingCollapse& p, VertexIndex removed, VertexIndex kept) {
    CollapseRecord record;
    record.removed = static_cast<int>(removed.idx());
    record.kept = static_cast<int>(kept.idx());
    for (const auto& face : p.patch.before) {
      FaceCorners corners;
      for (int k = 0; k < 3; ++k) corners[k] = static_cast<int>(p.vertex_of[face[k]].idx());
      record.before.push_back(corners);
    }
    for (const auto& face : p.patch.after) record.after.push_back(input_corners(p, face, kept));
    result_.collapses.push_back(std::move(record));
  }

  void report_progress() {
    const int total = finest_vertices_ - targets_.back();
    const int done = static_cast<int>(result_.collapses.size());
    if (!progress_ || (done % std::max(1, total / 100) != 0 && done != total)) return;
    if (!progress_(user_, static_cast<double>(done) / total, "decimation"))
      fail(Status::cancelled, "decimation: cancelled by the progress callback");
  }

  /// Snapshot of the live mesh as a level, with the anchors of the finest level's vertices
  /// and of the previous level's vertices on its faces.
  void record_level() {
    HierarchyLevel level;
    std::vector<int> vertex_row(sm_.num_vertices(), -1), face_row(sm_.num_faces(), -1);
    level.rest.vertices.resize(sm_.number_of_vertices(), 3);
    for (VertexIndex v : sm_.vertices()) {
      vertex_row[v.idx()] = static_cast<int>(level.input_vertex.size());
      level.rest.vertices.row(vertex_row[v.idx()]) = to_vec3(sm_.point(v)).transpose();
      level.input_vertex.push_back(static_cast<int>(v.idx()));
    }
    level.rest.faces.resize(sm_.number_of_faces(), 3);
    int row = 0;
    for (FaceIndex f : sm_.faces()) {
      const auto corners = face_corners(sm_, f);
      for (int k = 0; k < 3; ++k) level.rest.faces(row, k) = vertex_row[corners[k].idx()];
      face_row[f.idx()] = row++;
    }
    result_.to_finest.push_back(anchors_of(finest_points(), level, face_row));
    result_.to_next.push_back(anchors_of(last_level_points_, level, face_row));
    for (int id : last_level_points_)
      if (id >= finest_vertices_) points_[id].alive = false;
    result_.levels.push_back(std::move(level));
    result_.first_collapse.push_back(static_cast<int>(result_.collapses.size()));
    last_level_points_ = add_vertex_points();
    ++next_target_;
  }

  std::vector<int> finest_points() const {
    std::vector<int> ids(finest_vertices_);
    std::iota(ids.begin(), ids.end(), 0);
    return ids;
  }

  SurfaceAnchors anchors_of(const std::vector<int>& ids, const HierarchyLevel& level,
                            const std::vector<int>& face_row) const {
    SurfaceAnchors anchors(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const TrackedPoint& point = points_[ids[i]];
      SurfaceAnchor& anchor = anchors[i];
      anchor.face = face_row[point.face.idx()];
      for (int k = 0; k < 3; ++k) {
        const int input = level.input_vertex[level.rest.faces(anchor.face, k)];
        const auto at = std::find(point.corners.begin(), point.corners.end(), input);
        if (at == point.corners.end())
          fail(Status::internal, "decimation: a tracked point lost its face corners");
        anchor.weights[k] = point.weights[at - point.corners.begin()];
      }
    }
    return anchors;
  }

  SurfaceMesh& sm_;
  CollapseGuard guard_;
  std::vector<int> targets_;  ///< descending
  std::vector<int> group_;    ///< per input vertex: its group now (moves to kept vertices)
  std::size_t next_target_ = 0;
  HierarchyProgress progress_;
  void* user_;
  int finest_vertices_ = 0;
  SurfaceMesh::Property_map<FaceIndex, std::vector<int>> face_points_;
  std::vector<TrackedPoint> points_;  ///< the finest level's vertices first
  std::vector<int> last_level_points_;
  std::optional<PendingCollapse> pending_;
  MeshHierarchy result_;
};

/// CGAL placement: the quadric-optimal point (Garland and Heckbert 1997), except where an
/// endpoint must stay: on an edge touching the border, the border endpoint (so borders move
/// only where a border corner is cut off, and the flattening's border uv stays the merged
/// vertex's true position); on an edge touching a vertex group (a handle), the grouped
/// endpoint, at its rest position. Both endpoints border, or both in one group: the nearer to
/// the optimum. Two groups, or the two rules wanting different endpoints: no collapse. With
/// keep_input_positions, always an endpoint (the nearer). (Progsim choices, not in PSQ.)
template <class Base>
struct KeptVertexPlacement {
  Base base;
  const Tracker* tracker;
  bool keep_input_positions;
  template <class Profile>
  boost::optional<typename Profile::Point> operator()(const Profile& profile) const {
    const auto optimal = base(profile);
    if (!optimal) return optimal;
    const int g0 = tracker->groups()[profile.v0().idx()];
    const int g1 = tracker->groups()[profile.v1().idx()];
    if (g0 >= 0 && g1 >= 0 && g0 != g1) return boost::none;
    const auto& sm = profile.surface_mesh();
    const bool border0 = bool(CGAL::is_border(profile.v0(), sm));
    const bool border1 = bool(CGAL::is_border(profile.v1(), sm));
    const bool keep0 = (border0 && !border1) || (g0 >= 0 && g1 < 0);
    const bool keep1 = (border1 && !border0) || (g1 >= 0 && g0 < 0);
    if (keep0 && keep1) return boost::none;
    if (keep0 || keep1) return keep0 ? profile.p0() : profile.p1();
    if (!border0 && g0 < 0 && !keep_input_positions)
      return tracker->crossing_free_placement(profile, *optimal);
    const Vec3 p = to_vec3(*optimal);
    return (p - to_vec3(profile.p0())).squaredNorm() <= (p - to_vec3(profile.p1())).squaredNorm()
               ? profile.p0()
               : profile.p1();
  }
};

/// CGAL cost: the quadric error (Base), except 0 for an edge with an endpoint on a face that
/// crosses another in the input (a crossing start), so that such edges are collapsed first and
/// the guard lets only collapses that remove the crossing through. (A progsim choice.)
template <class Base>
struct CrossingFirstCost {
  using Update_tag = typename Base::Update_tag;  // CGAL updates Base's quadrics through these
  Base base;
  const Tracker* tracker;
  template <class Profile>
  boost::optional<typename Profile::FT> operator()(
      const Profile& profile, const boost::optional<typename Profile::Point>& placement) const {
    if (tracker->on_input_crossing(profile.v0()) || tracker->on_input_crossing(profile.v1()))
      return typename Profile::FT(0);
    return base(profile, placement);
  }
  template <class Mesh, class PointMap, class Traits>
  void initialize(const Mesh& mesh, const PointMap& points, const Traits& traits) const {
    base.initialize(mesh, points, traits);
  }
  template <class Profile, class Vertex>
  void update_after_collapse(const Profile& profile, const Vertex& kept) const {
    base.update_after_collapse(profile, kept);
  }
};

/// CGAL filter: bounded normal change, then the joint flattening and quality checks.
struct FlatteningFilter {
  Tracker* tracker;
  template <class Profile>
  boost::optional<typename Profile::Point> operator()(
      const Profile& profile, boost::optional<typename Profile::Point> placement) const {
    placement = SMS::Bounded_normal_change_filter<>()(profile, placement);
    if (placement && !tracker->prepare(profile, *placement)) return boost::none;
    return placement;
  }
};

/// CGAL visitor forwarding collapses to the tracker (CGAL stores visitors by value).
struct TrackingVisitor : SMS::Edge_collapse_visitor_base<SurfaceMesh> {
  Tracker* tracker;
  template <class Profile, class Placement>
  void OnCollapsing(const Profile& profile, const Placement&) {
    tracker->collapsing(profile);
  }
  template <class Profile>
  void OnCollapsed(const Profile& profile, VertexIndex kept) {
    tracker->collapsed(profile, kept);
  }
};

std::vector<int> checked_targets(std::vector<int> counts, int n) {
  std::sort(counts.begin(), counts.end(), std::greater<int>());
  for (std::size_t k = 0; k < counts.size(); ++k)
    if (counts[k] < 4 || counts[k] >= n || (k > 0 && counts[k] == counts[k - 1]))
      fail(Status::invalid_argument,
           "hierarchy: level vertex count " + std::to_string(counts[k]) +
               " must be distinct from the others, at least 4 and below the mesh's " +
               std::to_string(n) + " vertices");
  return counts;
}

/// The groups of the input vertices: all free if none given.
std::vector<int> checked_groups(std::vector<int> groups, int n) {
  if (groups.empty()) return std::vector<int>(n, -1);
  if (static_cast<int>(groups.size()) != n)
    fail(Status::invalid_argument, "hierarchy: " + std::to_string(groups.size()) +
                                       " vertex groups for " + std::to_string(n) + " vertices");
  for (int v = 0; v < n; ++v)
    if (groups[v] < -1)
      fail(Status::invalid_argument, "hierarchy: vertex " + std::to_string(v) + " has group " +
                                         std::to_string(groups[v]) + " (groups are -1 or more)");
  return groups;
}

/// The contact offsets: empty (crossings only) or one finite, non-negative value per vertex.
std::vector<double> checked_offsets(const HierarchyOptions& options, const TriangleMesh& mesh) {
  const std::vector<double>& offsets = options.contact_offsets;
  if (offsets.empty()) return offsets;
  if (static_cast<int>(offsets.size()) != mesh.num_vertices())
    fail(Status::invalid_argument, "hierarchy: " + std::to_string(offsets.size()) +
                                       " contact offsets for " +
                                       std::to_string(mesh.num_vertices()) + " vertices");
  for (std::size_t v = 0; v < offsets.size(); ++v)
    if (!(offsets[v] >= 0.0) || !std::isfinite(offsets[v]))
      fail(Status::invalid_argument, "hierarchy: vertex " + std::to_string(v) +
                                         " has contact offset " + std::to_string(offsets[v]) +
                                         " (a finite value >= 0 is needed)");
  return offsets;
}

}  // namespace

MeshHierarchy decimate(const TriangleMesh& mesh, const HierarchyOptions& options,
                       HierarchyProgress progress, void* user) {
  const std::vector<int> targets =
      checked_targets(options.coarse_vertex_counts, mesh.num_vertices());
  const std::vector<int> groups = checked_groups(options.vertex_groups, mesh.num_vertices());
  if (targets.empty()) {
    MeshHierarchy single;
    single.levels.push_back(input_level(mesh));
    single.input_group = groups;
    single.first_collapse.push_back(0);
    return single;
  }
  SurfaceMesh sm = to_surface_mesh(mesh);
  Tracker tracker(sm, CollapseGuard(mesh.vertices, mesh.faces, checked_offsets(options, mesh)),
                  targets, groups, progress, user);
  const int coarsest = targets.back();
  auto stop = [coarsest](const auto&, const auto& profile, std::size_t, std::size_t) {
    return static_cast<int>(profile.surface_mesh().number_of_vertices()) <= coarsest;
  };
  SMS::GarlandHeckbert_probabilistic_plane_policies<SurfaceMesh, Kernel> quadrics(sm);
  const KeptVertexPlacement<decltype(quadrics.get_placement())> placement{
      quadrics.get_placement(), &tracker, options.keep_input_positions};
  TrackingVisitor visitor;
  visitor.tracker = &tracker;
  const FlatteningFilter filter{&tracker};
  using Quadrics = std::remove_cv_t<std::remove_reference_t<decltype(quadrics.get_cost())>>;
  const CrossingFirstCost<Quadrics> cost{quadrics.get_cost(), &tracker};
  SMS::edge_collapse(
      sm, stop,
      CGAL::parameters::get_cost(cost).get_placement(placement).filter(filter).visitor(visitor));
  return tracker.finish(mesh);
}

}  // namespace progsim
