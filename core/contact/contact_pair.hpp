#pragma once
/// @file One primitive pair of contact (vertex–face, edge–edge or vertex–ground) on a collision
/// mesh: its stencil, its offset, its distance, and the conservative step that keeps it apart
/// along a linear motion (IPC, Li et al. 2020, §4; additive CCD of C-IPC, Li et al. 2021, Alg. 1).
#include <array>
#include <limits>

#include "contact/additive_ccd.hpp"
#include "contact/broad_phase.hpp"
#include "contact/collision_mesh.hpp"
#include "contact/primitive_distance.hpp"

namespace progsim {

/// An analytic ground for contact: the half-space normal·x ≥ height.
struct GroundPlane {
  Vec3 normal = Vec3::UnitY();  ///< unit
  double height = 0.0;          ///< m
  double friction = 0.0;        ///< μ
};

/// A pair's stencil in collision-vertex indices (−1 unused: the ground's) and its offset ξ, the
/// sum of the two sides' offsets (C-IPC §4).
struct ContactPair {
  enum class Kind { vertex_face, edge_edge, ground } kind;
  std::array<int, 4> vertices;
  double offset;  ///< m
};

/// Candidate k of `candidates`: the vertex–face ones first, then the edge–edge ones.
ContactPair candidate_pair(const CollisionMesh& mesh, const CandidateSet& candidates, int k);

/// Shell vertex v against the ground.
ContactPair ground_pair(const CollisionMesh& mesh, int v);

/// The stencil's positions stacked (12; zero for unused vertices).
Vec12 stencil_positions(const std::array<int, 4>& vertices, const Positions& p);

/// Unsigned squared distance of a pair at stencil positions xs (0 for a vertex below the
/// ground); for vertex–face and edge–edge pairs also the closest sub-primitives when non-null.
double pair_distance_squared(const ContactPair& pair, const Vec12& xs, const GroundPlane* ground,
                             ClosestPair* closest = nullptr);

/// Largest safe step t ∈ [0, 1] of the pair along xs + t·dx that keeps its distance above
/// `offset` and, when t < 1, at least offset + s·(d − offset) (additive CCD, C-IPC Alg. 1;
/// for the ground in closed form). `ground` is needed for ground pairs only; `max_iterations`
/// caps the additive CCD's iterations; the result is min(t, stop_at) (see
/// additive_ccd_point_triangle()).
double pair_safe_step(const ContactPair& pair, const Vec12& xs, const Vec12& dx, double offset,
                      double s, const GroundPlane* ground, int max_iterations = kAccdMaxIterations,
                      double stop_at = std::numeric_limits<double>::infinity());

}  // namespace progsim
