#include "mesh/mesh_validation.hpp"

#include <cmath>
#include <numeric>
#include <sstream>
#include <vector>

#include "mesh/element_checks.hpp"
#include "mesh/half_edges.hpp"

namespace progsim {
namespace {

/// Faces whose area is at most this fraction of the squared bounding-box diagonal count as
/// degenerate. Relative, so that slivers with tiny angles but a real area pass.
constexpr double kDegenerateAreaFraction = 1e-14;

/// "(a, b, c)" for face f.
std::string face_string(const Faces& faces, int f) {
  std::ostringstream s;
  s << '(' << faces(f, 0) << ", " << faces(f, 1) << ", " << faces(f, 2) << ')';
  return s.str();
}

void check_not_empty(const TriangleMesh& mesh, const std::string& label) {
  if (mesh.num_faces() == 0)
    reject_mesh(label,
                "the mesh has no faces (" + std::to_string(mesh.num_vertices()) + " vertices)");
}

void check_distinct_corners(const TriangleMesh& mesh, const std::string& label) {
  const Faces& F = mesh.faces;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (F(f, 0) != F(f, 1) && F(f, 1) != F(f, 2) && F(f, 2) != F(f, 0)) continue;
    reject_mesh(label, "face " + std::to_string(f) + " repeats a vertex: " + face_string(F, f));
  }
}

void check_areas(const TriangleMesh& mesh, const std::string& label) {
  const double diagonal = bounding_box_diagonal(mesh.vertices);
  const double threshold = kDegenerateAreaFraction * diagonal * diagonal;
  const Eigen::VectorXd areas = face_areas(mesh.vertices, mesh.faces);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (areas[f] > threshold) continue;
    std::ostringstream s;
    s << "face " << f << " is degenerate (area " << areas[f] << " m²)";
    reject_mesh(label, s.str());
  }
}

std::string edge_string(const HalfEdge& h) {
  return "edge (" + std::to_string(h.lo) + ", " + std::to_string(h.hi) + ")";
}

/// Every edge has at most two faces, and two faces traverse it in opposite directions.
void check_edges(const TriangleMesh& mesh, const std::vector<HalfEdge>& half_edges,
                 const std::string& label) {
  for_each_edge(half_edges, [&](std::size_t first, std::size_t count) {
    if (count <= 2) return;
    reject_mesh(label, edge_string(half_edges[first]) + " is shared by " + std::to_string(count) +
                           " faces (non-manifold)");
  });
  for_each_edge(half_edges, [&](std::size_t first, std::size_t count) {
    const HalfEdge& a = half_edges[first];
    if (count < 2) return;
    const HalfEdge& b = half_edges[first + 1];
    if (runs_forward(a, mesh.faces) != runs_forward(b, mesh.faces)) return;
    reject_mesh(label, edge_string(a) + " is traversed in the same direction by faces " +
                           std::to_string(a.face) + " and " + std::to_string(b.face) +
                           " (inconsistent orientation)");
  });
}

/// Disjoint sets over the 3|F| face corners (corner 3f + k is vertex faces(f, k) of face f).
class CornerSets {
 public:
  explicit CornerSets(int num_corners) : parent_(num_corners) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int c) {
    while (parent_[c] != c) c = parent_[c] = parent_[parent_[c]];
    return c;
  }
  void unite(int a, int b) { parent_[find(a)] = find(b); }

 private:
  std::vector<int> parent_;
};

/// The faces around each vertex form one fan: corners of a vertex are linked through the
/// interior edges at that vertex, and a vertex with two unlinked groups is a bow-tie.
void check_vertex_fans(const TriangleMesh& mesh, const std::vector<HalfEdge>& half_edges,
                       const std::string& label) {
  CornerSets fans(3 * mesh.num_faces());
  for_each_edge(half_edges, [&](std::size_t first, std::size_t count) {
    if (count != 2) return;
    const HalfEdge& a = half_edges[first];
    const HalfEdge& b = half_edges[first + 1];
    // Opposite directions: the start corner of one side meets the end corner of the other.
    fans.unite(3 * a.face + a.side, 3 * b.face + (b.side + 1) % 3);
    fans.unite(3 * a.face + (a.side + 1) % 3, 3 * b.face + b.side);
  });
  std::vector<int> first_corner(mesh.num_vertices(), -1);
  int bow_tie = -1, face_a = -1, face_b = -1;
  for (int c = 0; c < 3 * mesh.num_faces(); ++c) {
    const int v = mesh.faces(c / 3, c % 3);
    if (first_corner[v] < 0) {
      first_corner[v] = c;
    } else if (fans.find(c) != fans.find(first_corner[v]) && (bow_tie < 0 || v < bow_tie)) {
      bow_tie = v, face_a = first_corner[v] / 3, face_b = c / 3;
    }
  }
  if (bow_tie < 0) return;
  reject_mesh(label, "vertex " + std::to_string(bow_tie) +
                         " is a non-manifold (bow-tie) vertex: faces " + std::to_string(face_a) +
                         " and " + std::to_string(face_b) +
                         " touch there but are not connected through the edges around it");
}

}  // namespace

void validate_mesh(const TriangleMesh& mesh, const std::string& label) {
  check_not_empty(mesh, label);
  check_finite_vertices(mesh.vertices, label);
  check_element_indices(mesh.faces, mesh.num_vertices(), "face", label);
  check_distinct_corners(mesh, label);
  check_areas(mesh, label);
  const std::vector<HalfEdge> half_edges = sorted_half_edges(mesh.faces, mesh.num_vertices());
  check_edges(mesh, half_edges, label);
  check_vertex_fans(mesh, half_edges, label);
  check_referenced_vertices(mesh.faces, mesh.num_vertices(), "face", label);
}

}  // namespace progsim
