#include "contact/contact_pair.hpp"

#include <algorithm>
#include <limits>

#include "contact/additive_ccd.hpp"

namespace progsim {

ContactPair candidate_pair(const CollisionMesh& mesh, const CandidateSet& candidates, int k) {
  const int num_vf = static_cast<int>(candidates.vertex_face.size());
  if (k < num_vf) {
    const auto [v, f] = candidates.vertex_face[k];
    const auto face = mesh.faces.row(f);
    return {ContactPair::Kind::vertex_face,
            {v, face[0], face[1], face[2]},
            mesh.vertex_offset[v] + mesh.vertex_offset[face[0]]};
  }
  const auto [a, b] = candidates.edge_edge[k - num_vf];
  const auto& ea = mesh.edges[a];
  const auto& eb = mesh.edges[b];
  return {ContactPair::Kind::edge_edge,
          {ea[0], ea[1], eb[0], eb[1]},
          mesh.vertex_offset[ea[0]] + mesh.vertex_offset[eb[0]]};
}

ContactPair ground_pair(const CollisionMesh& mesh, int v) {
  return {ContactPair::Kind::ground, {v, -1, -1, -1}, mesh.vertex_offset[v]};
}

Vec12 stencil_positions(const std::array<int, 4>& vertices, const Positions& p) {
  Vec12 xs = Vec12::Zero();
  for (int k = 0; k < 4; ++k)
    if (vertices[k] >= 0) xs.segment<3>(3 * k) = p.row(vertices[k]).transpose();
  return xs;
}

double pair_distance_squared(const ContactPair& pair, const Vec12& xs, const GroundPlane* ground,
                             ClosestPair* closest) {
  if (pair.kind == ContactPair::Kind::ground) {
    const double signed_distance = ground->normal.dot(xs.head<3>()) - ground->height;
    return signed_distance > 0.0 ? signed_distance * signed_distance : 0.0;  // below: touching
  }
  const ClosestPair c = pair.kind == ContactPair::Kind::vertex_face ? classify_point_triangle(xs)
                                                                    : classify_edge_edge(xs);
  if (closest) *closest = c;
  return distance_squared(xs, c);
}

double pair_safe_step(const ContactPair& pair, const Vec12& xs, const Vec12& dx, double offset,
                      double s, const GroundPlane* ground, int max_iterations, double stop_at) {
  if (!xs.allFinite() || !dx.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  switch (pair.kind) {
    case ContactPair::Kind::ground: {
      const double approach = -ground->normal.dot(dx.head<3>());
      const double gap = ground->normal.dot(xs.head<3>()) - ground->height - offset;
      return std::min(approach > 0.0 ? std::clamp((1.0 - s) * gap / approach, 0.0, 1.0) : 1.0,
                      stop_at);
    }
    case ContactPair::Kind::vertex_face:
      return additive_ccd_point_triangle(xs, dx, offset, s, 1.0, max_iterations, stop_at);
    case ContactPair::Kind::edge_edge:
      return additive_ccd_edge_edge(xs, dx, offset, s, 1.0, max_iterations, stop_at);
  }
  return 0.0;
}

}  // namespace progsim
