// The only translation unit that includes CGAL's Polygon_mesh_processing (slow to compile).
#include "mesh/intersection_check.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <sstream>
#include <utility>

#include "common/error.hpp"

namespace progsim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using FaceIndex = SurfaceMesh::Face_index;

/// The mesh as a CGAL halfedge structure with shared vertices, so that CGAL tells
/// neighbouring faces (sharing an edge or a vertex) from intersecting ones. Face f of the
/// result is faces.row(f). Throws Error(invalid_mesh) for a face CGAL cannot add
/// (non-manifold or inconsistently oriented).
SurfaceMesh surface_mesh(const Positions& positions, const Faces& faces) {
  SurfaceMesh mesh;
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    mesh.add_vertex(Kernel::Point_3(positions(v, 0), positions(v, 1), positions(v, 2)));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const auto corner = [&](int k) { return SurfaceMesh::Vertex_index(faces(f, k)); };
    if (mesh.add_face(corner(0), corner(1), corner(2)) == SurfaceMesh::null_face())
      fail(Status::invalid_mesh, "intersection check: face " + std::to_string(f) +
                                     " makes the mesh non-manifold or inconsistently oriented");
  }
  return mesh;
}

}  // namespace

std::vector<FacePair> intersecting_faces(const Positions& positions, const Faces& faces,
                                         std::size_t max_pairs) {
  const SurfaceMesh mesh = surface_mesh(positions, faces);
  std::vector<std::pair<FaceIndex, FaceIndex>> hits;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(hits));
  std::vector<FacePair> pairs;
  for (const auto& [fa, fb] : hits) {
    const int a = static_cast<int>(fa), b = static_cast<int>(fb);
    pairs.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(pairs.begin(), pairs.end(), [](const FacePair& x, const FacePair& y) {
    return std::pair(x.a, x.b) < std::pair(y.a, y.b);
  });
  if (max_pairs > 0 && pairs.size() > max_pairs) pairs.resize(max_pairs);
  return pairs;
}

void check_intersection_free(const Positions& positions, const Faces& faces,
                             const std::string& label) {
  const std::vector<FacePair> pairs = intersecting_faces(positions, faces, 1);
  if (pairs.empty()) return;
  const auto face_text = [&](int f) {
    std::ostringstream s;
    s << f << " (vertices " << faces(f, 0) << ", " << faces(f, 1) << ", " << faces(f, 2) << ")";
    return s.str();
  };
  fail(Status::intersecting,
       label + ": faces " + face_text(pairs[0].a) + " and " + face_text(pairs[0].b) + " intersect");
}

}  // namespace progsim
