#include "mesh/half_edges.hpp"

#include <algorithm>
#include <tuple>

namespace progsim {

std::vector<HalfEdge> sorted_half_edges(const Faces& faces, int num_vertices) {
  // Counting sort by the lower vertex, then a small sort inside each bucket: O(|F|) buckets
  // of a few entries each.
  std::vector<int> bucket_start(num_vertices + 1, 0);
  for (int f = 0; f < faces.rows(); ++f)
    for (int side = 0; side < 3; ++side)
      ++bucket_start[std::min(faces(f, side), faces(f, (side + 1) % 3)) + 1];
  for (int v = 0; v < num_vertices; ++v) bucket_start[v + 1] += bucket_start[v];

  std::vector<HalfEdge> half_edges(3 * static_cast<std::size_t>(faces.rows()));
  std::vector<int> next = bucket_start;
  for (int f = 0; f < faces.rows(); ++f) {
    for (int side = 0; side < 3; ++side) {
      const int a = faces(f, side), b = faces(f, (side + 1) % 3);
      half_edges[next[std::min(a, b)]++] = HalfEdge{std::min(a, b), std::max(a, b), f, side};
    }
  }
  for (int v = 0; v < num_vertices; ++v) {
    std::sort(half_edges.begin() + bucket_start[v], half_edges.begin() + bucket_start[v + 1],
              [](const HalfEdge& x, const HalfEdge& y) {
                return std::tie(x.hi, x.face) < std::tie(y.hi, y.face);
              });
  }
  return half_edges;
}

}  // namespace progsim
