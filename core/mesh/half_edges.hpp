#pragma once
/// @file Internal to core/mesh: the directed edges of all faces, grouped by undirected edge.
/// Shared by mesh validation and topology so that both see the same edge order.
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// Side `side` of face `face`: it runs faces(face, side) → faces(face, (side + 1) % 3).
/// `lo` < `hi` are its two vertices, independent of direction.
struct HalfEdge {
  int lo, hi;  ///< the undirected edge
  int face;    ///< the face this side belongs to
  int side;    ///< 0, 1 or 2
};

/// All 3|F| half-edges, sorted by (lo, hi) and then by face. Precondition: indices lie in
/// [0, num_vertices) and no face repeats a vertex.
std::vector<HalfEdge> sorted_half_edges(const Faces& faces, int num_vertices);

/// True if `h` runs lo → hi in its face.
inline bool runs_forward(const HalfEdge& h, const Faces& faces) {
  return faces(h.face, h.side) == h.lo;
}

/// Calls fn(first, count) for each run of `count` half-edges sharing one undirected edge,
/// in sorted edge order; `first` indexes `half_edges`.
template <class Fn>
void for_each_edge(const std::vector<HalfEdge>& half_edges, Fn&& fn) {
  for (std::size_t first = 0; first < half_edges.size();) {
    std::size_t end = first + 1;
    while (end < half_edges.size() && half_edges[end].lo == half_edges[first].lo &&
           half_edges[end].hi == half_edges[first].hi)
      ++end;
    fn(first, end - first);
    first = end;
  }
}

}  // namespace progsim
