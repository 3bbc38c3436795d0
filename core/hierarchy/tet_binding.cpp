#include "hierarchy/tet_binding.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <limits>
#include <queue>
#include <utility>

#include "mesh/tet_boundary.hpp"
#include "mesh/triangle_mesh.hpp"

namespace progsim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Ray = Kernel::Ray_3;
using Triangles = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int,
                                                      CGAL::Box_intersection_d::ID_EXPLICIT>;

/// Barycentric slack within which a vertex counts as inside a tet (relative to 1).
constexpr double kContainmentTolerance = 1e-9;

Point point(const Positions& v, int i) {
  return Point(v(i, 0), v(i, 1), v(i, 2));
}

std::array<Point, 4> corners(const TetMesh& m, int t) {
  return {point(m.vertices, m.tets(t, 0)), point(m.vertices, m.tets(t, 1)),
          point(m.vertices, m.tets(t, 2)), point(m.vertices, m.tets(t, 3))};
}

/// p lies in the closed tet t: replacing any corner by p never turns the orientation negative.
bool contains(const TetMesh& m, int t, const Point& p) {
  const std::array<Point, 4> c = corners(m, t);
  for (int k = 0; k < 4; ++k) {
    std::array<Point, 4> q = c;
    q[k] = p;
    if (CGAL::orientation(q[0], q[1], q[2], q[3]) == CGAL::NEGATIVE) return false;
  }
  return true;
}

/// Squared distance from p to the closed tet t (0 inside).
double squared_distance_to_tet(const TetMesh& m, int t, const Point& p) {
  if (contains(m, t, p)) return 0.0;
  const std::array<Point, 4> c = corners(m, t);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k)
    best = std::min(best, CGAL::to_double(CGAL::squared_distance(
                              p, Triangle(c[(k + 1) % 4], c[(k + 2) % 4], c[(k + 3) % 4]))));
  return best;
}

/// For each fine vertex the lowest-index coarse tet containing it, or −1: CGAL's box
/// intersection of the vertices with the tets' bounding boxes, then the exact containment test.
std::vector<int> containing_tets(const TetMesh& coarse, const Positions& points) {
  std::vector<Box> tet_boxes, point_boxes;
  tet_boxes.reserve(coarse.num_tets());
  for (int t = 0; t < coarse.num_tets(); ++t) {
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      lo[d] = hi[d] = coarse.vertices(coarse.tets(t, 0), d);
      for (int k = 1; k < 4; ++k) {
        lo[d] = std::min(lo[d], coarse.vertices(coarse.tets(t, k), d));
        hi[d] = std::max(hi[d], coarse.vertices(coarse.tets(t, k), d));
      }
    }
    tet_boxes.emplace_back(lo, hi, t);
  }
  // Points are boxes grown by a hair so that tets they miss by rounding are found too.
  const double hair = kContainmentTolerance * bounding_box_diagonal(coarse.vertices);
  point_boxes.reserve(points.rows());
  for (int i = 0; i < points.rows(); ++i) {
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      lo[d] = points(i, d) - hair;
      hi[d] = points(i, d) + hair;
    }
    point_boxes.emplace_back(lo, hi, i);
  }
  std::vector<int> home(points.rows(), -1);
  std::vector<double> score(points.rows(), -kContainmentTolerance);
  CGAL::box_intersection_d(point_boxes.begin(), point_boxes.end(), tet_boxes.begin(),
                           tet_boxes.end(), [&](const Box& p, const Box& t) {
                             const int i = p.info(), tet = t.info();
                             const Eigen::Vector3d x = points.row(i).transpose();
                             // Exact containment scores above any weight; otherwise the smallest
                             // weight, which must be at least −tolerance: a vertex a mesher left an
                             // ulp outside a shared plane.
                             const double s =
                                 contains(coarse, tet, point(points, i))
                                     ? 2.0
                                     : tet_barycentric_weights(coarse, tet, x).minCoeff();
                             if (s > score[i] || (s == score[i] && home[i] >= 0 && tet < home[i])) {
                               score[i] = s;
                               home[i] = tet;
                             }
                           });
  return home;
}

/// Vertex–vertex adjacency of a tet mesh (its tets' edges), CSR, each list sorted.
struct Adjacency {
  std::vector<int> offsets, neighbors;
  explicit Adjacency(const TetMesh& m) {
    std::vector<std::pair<int, int>> edges;
    for (int t = 0; t < m.num_tets(); ++t)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          if (a != b) edges.emplace_back(m.tets(t, a), m.tets(t, b));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    offsets.assign(m.num_vertices() + 1, 0);
    for (const auto& e : edges) ++offsets[e.first + 1];
    for (int v = 0; v < m.num_vertices(); ++v) offsets[v + 1] += offsets[v];
    for (const auto& e : edges) neighbors.push_back(e.second);
  }
};

/// The coarse boundary faces as CGAL triangles in an AABB tree, with the tet behind each.
class CoarseBoundary {
 public:
  explicit CoarseBoundary(const TetMesh& coarse) {
    const TetBoundary boundary = extract_tet_boundary(coarse);
    face_tet_ = boundary.face_tet;
    const Positions& v = boundary.surface.vertices;
    for (int f = 0; f < boundary.surface.num_faces(); ++f)
      triangles_.emplace_back(point(v, boundary.surface.faces(f, 0)),
                              point(v, boundary.surface.faces(f, 1)),
                              point(v, boundary.surface.faces(f, 2)));
    tree_.insert(triangles_.begin(), triangles_.end());
    tree_.accelerate_distance_queries();
  }

  /// The tet behind the first face the ray from `from` through `toward` hits, with the squared
  /// distance to the hit; (−1, ∞) without a hit.
  std::pair<int, double> first_hit(const Point& from, const Point& toward) const {
    const auto hit = tree_.first_intersection(Ray(from, toward));
    if (!hit) return {-1, std::numeric_limits<double>::infinity()};
    const int face = static_cast<int>(hit->second - triangles_.begin());
    double distance = 0.0;
    if (const Point* p = boost::get<Point>(&hit->first))
      distance = CGAL::to_double(CGAL::squared_distance(from, *p));
    else if (const auto* s = boost::get<Kernel::Segment_3>(&hit->first))
      distance = CGAL::to_double(CGAL::squared_distance(from, *s));
    return {face_tet_[face], distance};
  }

  /// The tet behind the boundary face nearest to p.
  int nearest(const Point& p) const {
    return face_tet_[tree_.closest_point_and_primitive(p).second - triangles_.begin()];
  }

 private:
  Triangles triangles_;
  std::vector<int> face_tet_;
  Tree tree_;
};

/// The home of an unbound vertex v (VPD §3.3.3): the closest ray hit along its edges, else the
/// closest of its bound neighbours' tets, else the tet of the nearest boundary face.
std::pair<int, BindingKind> find_home(const TetMesh& coarse, const CoarseBoundary& boundary,
                                      const Positions& fine, const Adjacency& adjacency,
                                      const std::vector<int>& home, int v) {
  const Point p = point(fine, v);
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int i = adjacency.offsets[v]; i < adjacency.offsets[v + 1]; ++i) {
    const auto [tet, distance] = boundary.first_hit(p, point(fine, adjacency.neighbors[i]));
    if (tet >= 0 && distance < best_distance)
      std::tie(best, best_distance) = std::tie(tet, distance);
  }
  if (best >= 0) return {best, BindingKind::ray};
  for (int i = adjacency.offsets[v]; i < adjacency.offsets[v + 1]; ++i) {
    const int tet = home[adjacency.neighbors[i]];
    if (tet < 0) continue;
    const double distance = squared_distance_to_tet(coarse, tet, p);
    if (distance < best_distance) std::tie(best, best_distance) = std::tie(tet, distance);
  }
  if (best >= 0) return {best, BindingKind::neighbor};
  return {boundary.nearest(p), BindingKind::nearest};
}

}  // namespace

Eigen::Vector4d tet_barycentric_weights(const TetMesh& mesh, int t, const Eigen::Vector3d& p) {
  const Eigen::Vector3d x0 = mesh.vertices.row(mesh.tets(t, 0)).transpose();
  Mat3 d;
  for (int k = 0; k < 3; ++k) d.col(k) = mesh.vertices.row(mesh.tets(t, k + 1)).transpose() - x0;
  const Eigen::Vector3d w = d.partialPivLu().solve(p - x0);  // p = x₀ + D w
  return Eigen::Vector4d(1.0 - w.sum(), w.x(), w.y(), w.z());
}

std::vector<TetBinding> bind_to_tets(const TetMesh& coarse, const TetMesh& fine) {
  std::vector<int> home = containing_tets(coarse, fine.vertices);
  std::vector<BindingKind> kind(home.size(), BindingKind::inside);
  const Adjacency adjacency(fine);
  std::vector<int> bound_neighbors(home.size(), 0);
  std::priority_queue<std::pair<int, int>> queue;  // (bound neighbours, −vertex): most first
  for (int v = 0; v < fine.num_vertices(); ++v) {
    if (home[v] >= 0) continue;
    for (int i = adjacency.offsets[v]; i < adjacency.offsets[v + 1]; ++i)
      bound_neighbors[v] += home[adjacency.neighbors[i]] >= 0;
    queue.emplace(bound_neighbors[v], -v);
  }
  if (!queue.empty()) {
    const CoarseBoundary boundary(coarse);
    while (!queue.empty()) {
      const auto [count, negated] = queue.top();
      queue.pop();
      const int v = -negated;
      if (home[v] >= 0 || count != bound_neighbors[v]) continue;  // bound, or a stale entry
      std::tie(home[v], kind[v]) = find_home(coarse, boundary, fine.vertices, adjacency, home, v);
      for (int i = adjacency.offsets[v]; i < adjacency.offsets[v + 1]; ++i) {
        const int u = adjacency.neighbors[i];
        if (home[u] < 0) queue.emplace(++bound_neighbors[u], -u);
      }
    }
  }
  std::vector<TetBinding> bindings(home.size());
  for (int v = 0; v < fine.num_vertices(); ++v)
    bindings[v] = {home[v], tet_barycentric_weights(coarse, home[v], fine.vertices.row(v)),
                   kind[v]};
  return bindings;
}

}  // namespace progsim
