#include "mesh/tet_mesh_validation.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <sstream>
#include <tuple>
#include <vector>

#include "mesh/element_checks.hpp"
#include "mesh/half_edges.hpp"
#include "mesh/tet_faces.hpp"
#include "mesh/triangle_mesh.hpp"

namespace progsim {
namespace {

/// Tets whose volume is at most this fraction of the cubed bounding-box diagonal count as
/// degenerate. Relative, so that slivers with tiny angles but a real volume pass.
constexpr double kDegenerateVolumeFraction = 1e-14;

/// "(a, b, c, d)" for tet t.
std::string tet_string(const Tets& tets, int t) {
  std::ostringstream s;
  s << '(' << tets(t, 0) << ", " << tets(t, 1) << ", " << tets(t, 2) << ", " << tets(t, 3) << ')';
  return s.str();
}

std::string face_string(const std::array<int, 3>& face) {
  std::ostringstream s;
  s << "face (" << face[0] << ", " << face[1] << ", " << face[2] << ')';
  return s.str();
}

void check_not_empty(const TetMesh& mesh, const std::string& label) {
  if (mesh.num_tets() == 0)
    reject_mesh(label,
                "the mesh has no tets (" + std::to_string(mesh.num_vertices()) + " vertices)");
}

void check_distinct_corners(const TetMesh& mesh, const std::string& label) {
  for (int t = 0; t < mesh.num_tets(); ++t) {
    std::array<int, 4> corners{};
    Eigen::Map<Eigen::RowVector4i>(corners.data()) = mesh.tets.row(t);
    std::sort(corners.begin(), corners.end());
    if (std::adjacent_find(corners.begin(), corners.end()) == corners.end()) continue;
    reject_mesh(label,
                "tet " + std::to_string(t) + " repeats a vertex: " + tet_string(mesh.tets, t));
  }
}

void check_volumes(const TetMesh& mesh, const std::string& label) {
  const double diagonal = bounding_box_diagonal(mesh.vertices);
  const double threshold = kDegenerateVolumeFraction * diagonal * diagonal * diagonal;
  const Eigen::VectorXd volumes = tet_signed_volumes(mesh.vertices, mesh.tets);
  for (int t = 0; t < mesh.num_tets(); ++t) {
    if (volumes[t] > threshold) continue;
    std::ostringstream s;
    s << "tet " << t << ' ' << tet_string(mesh.tets, t);
    if (volumes[t] < -threshold)
      s << " is inverted (signed volume " << volumes[t]
        << " m³; its corners are ordered against the convention of tet_mesh.hpp)";
    else
      s << " is degenerate (volume " << volumes[t] << " m³)";
    reject_mesh(label, s.str());
  }
}

/// No two tets on the same vertex set (in any order).
void check_duplicates(const TetMesh& mesh, const std::string& label) {
  std::vector<std::pair<std::array<int, 4>, int>> keys(mesh.num_tets());
  for (int t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Map<Eigen::RowVector4i>(keys[t].first.data()) = mesh.tets.row(t);
    std::sort(keys[t].first.begin(), keys[t].first.end());
    keys[t].second = t;
  }
  std::sort(keys.begin(), keys.end());
  const auto same_set = [](const auto& a, const auto& b) { return a.first == b.first; };
  const auto duplicate = std::adjacent_find(keys.begin(), keys.end(), same_set);
  if (duplicate == keys.end()) return;
  reject_mesh(label, "tets " + std::to_string(duplicate->second) + " and " +
                         std::to_string(std::next(duplicate)->second) + " are duplicates (both " +
                         tet_string(mesh.tets, duplicate->second) + " up to order)");
}

/// Every face has at most two tets, and two tets traverse it in opposite orientations.
void check_faces(const Tets& tets, const std::vector<TetFace>& faces, const std::string& label) {
  for_each_face(faces, [&](std::size_t first, std::size_t count) {
    const TetFace& a = faces[first];
    if (count > 2)
      reject_mesh(label, face_string(a.key) + " is shared by " + std::to_string(count) + " tets (" +
                             std::to_string(a.tet) + ", " + std::to_string(faces[first + 1].tet) +
                             ", " + std::to_string(faces[first + 2].tet) + ", ...; non-manifold)");
    if (count < 2) return;
    const TetFace& b = faces[first + 1];
    if (!same_orientation(oriented_face(tets, a.tet, a.local), oriented_face(tets, b.tet, b.local)))
      return;
    reject_mesh(label, "tets " + std::to_string(a.tet) + " and " + std::to_string(b.tet) +
                           " traverse " + face_string(a.key) +
                           " in the same orientation (they overlap on the same side of it)");
  });
}

/// Every boundary edge lies on exactly two boundary faces, traversed in opposite directions.
void check_boundary_edges(const Faces& boundary, int num_vertices, const std::string& label) {
  const std::vector<HalfEdge> half_edges = sorted_half_edges(boundary, num_vertices);
  for_each_edge(half_edges, [&](std::size_t first, std::size_t count) {
    const HalfEdge& a = half_edges[first];
    const std::string edge = "edge (" + std::to_string(a.lo) + ", " + std::to_string(a.hi) + ")";
    if (count != 2)
      reject_mesh(label, edge + " lies on " + std::to_string(count) +
                             " boundary faces, not 2: the boundary is not a closed 2-manifold "
                             "(non-manifold edge)");
    if (runs_forward(a, boundary) != runs_forward(half_edges[first + 1], boundary)) return;
    reject_mesh(label, edge +
                           " is traversed in the same direction by two boundary faces "
                           "(inconsistent boundary orientation)");
  });
}

/// One corner of a boundary face seen from its vertex: the face's other two vertices in order.
struct LinkEdge {
  int vertex, from, to;
  bool operator<(const LinkEdge& o) const {
    return std::tie(vertex, from) < std::tie(o.vertex, o.from);
  }
};

/// The boundary faces around each boundary vertex form a single fan: walking its link (a cycle
/// once the edges are manifold) from one edge visits all of them. A bow-tie vertex has two.
void check_boundary_vertices(const Faces& boundary, const std::string& label) {
  std::vector<LinkEdge> link;
  link.reserve(3 * static_cast<std::size_t>(boundary.rows()));
  for (Eigen::Index f = 0; f < boundary.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      link.push_back({boundary(f, k), boundary(f, (k + 1) % 3), boundary(f, (k + 2) % 3)});
  std::sort(link.begin(), link.end());
  for (auto first = link.begin(); first != link.end();) {
    const auto end = std::upper_bound(first, link.end(), LinkEdge{first->vertex, INT_MAX, 0});
    std::ptrdiff_t visited = 0;
    for (int at = first->to; visited < end - first; ++visited) {
      const auto next = std::lower_bound(first, end, LinkEdge{first->vertex, at, 0});
      if (next == end || next->from != at || at == first->from) break;
      at = next->to;
    }
    if (visited + 1 < end - first)
      reject_mesh(label,
                  "vertex " + std::to_string(first->vertex) +
                      " is a non-manifold (bow-tie) boundary vertex: its boundary faces form "
                      "more than one fan (the mesh touches itself there)");
    first = end;
  }
}

}  // namespace

void validate_tet_mesh(const TetMesh& mesh, const std::string& label) {
  check_not_empty(mesh, label);
  check_finite_vertices(mesh.vertices, label);
  check_element_indices(mesh.tets, mesh.num_vertices(), "tet", label);
  check_distinct_corners(mesh, label);
  check_volumes(mesh, label);
  check_duplicates(mesh, label);
  const std::vector<TetFace> faces = sorted_tet_faces(mesh.tets);
  check_faces(mesh.tets, faces, label);
  const Faces boundary = boundary_faces(faces, mesh.tets);
  check_boundary_edges(boundary, mesh.num_vertices(), label);
  check_boundary_vertices(boundary, label);
  check_referenced_vertices(mesh.tets, mesh.num_vertices(), "tet", label);
}

}  // namespace progsim
