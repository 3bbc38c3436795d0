#include "mesh/mesh_topology.hpp"

#include "mesh/half_edges.hpp"

namespace progsim {
namespace {

/// The corner of h's face opposite the side h.
int opposite_vertex(const Faces& faces, const HalfEdge& h) {
  return faces(h.face, (h.side + 2) % 3);
}

/// The hinge of an interior edge whose two half-edges are `first` (the lower face) and
/// `second`: oriented so that the edge runs v0 → v1 in the first face.
Hinge make_hinge(const Faces& faces, const HalfEdge& first, const HalfEdge& second) {
  Hinge hinge;
  hinge.v0 = faces(first.face, first.side);
  hinge.v1 = faces(first.face, (first.side + 1) % 3);
  hinge.v2 = opposite_vertex(faces, first);
  hinge.v3 = opposite_vertex(faces, second);
  hinge.f0 = first.face;
  hinge.f1 = second.face;
  return hinge;
}

}  // namespace

MeshTopology build_topology(const Faces& faces, int num_vertices) {
  const std::vector<HalfEdge> half_edges = sorted_half_edges(faces, num_vertices);
  MeshTopology topology;
  for_each_edge(half_edges, [&](std::size_t first, std::size_t count) {
    const HalfEdge& h = half_edges[first];
    topology.edges.push_back({h.lo, h.hi});
    topology.edge_on_boundary.push_back(count == 1);
    if (count == 2) topology.hinges.push_back(make_hinge(faces, h, half_edges[first + 1]));
  });
  return topology;
}

double mean_edge_length(const MeshTopology& topology, const Positions& positions) {
  if (topology.edges.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& [a, b] : topology.edges) sum += (positions.row(a) - positions.row(b)).norm();
  return sum / static_cast<double>(topology.edges.size());
}

}  // namespace progsim
