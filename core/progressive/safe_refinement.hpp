#pragma once
/// @file Safe refinement of one hierarchy level into the next under contact (PSQ, Zhang et al.
/// 2023, §4.4, Algorithms 2–5): vertex splits batch by batch, each new vertex nudged off its
/// partner in a locally safe direction, then every split advanced toward its prolonged target
/// with additive CCD, stopping the stencils that bound the step and continuing with the rest.
/// The result is intersection-free wherever the coarse state was, and close to the target.
#include <cstdint>
#include <optional>
#include <vector>

#include "contact/contact_pair.hpp"
#include "hierarchy/mesh_hierarchy.hpp"

namespace progsim {

/// What the refined shell must stay clear of, and its own contact offsets.
struct RefinementSurroundings {
  std::vector<double> vertex_offset;  ///< ξ per vertex of the finer level (m)
  Positions obstacle_positions;       ///< (|V_o| × 3) obstacle vertices now (may be empty)
  Faces obstacle_faces;               ///< (|F_o| × 3) into obstacle_positions
  std::optional<GroundPlane> ground;  ///< the analytic ground, if any
  double dhat = 1e-3;                 ///< activation gap d̂ (m): the gap g₀ is capped by it
};

class ContactPotential;
struct ShellModel;

/// What the shell `finer` (the level refined into) must stay clear of during refinement: its
/// contact offsets, the obstacles where `contact` has them now, the ground.
RefinementSurroundings refinement_surroundings(const ContactPotential& contact,
                                               const ShellModel& finer);

/// Parameters of PSQ Algorithms 3–5.
struct SafeRefinementSettings {
  /// A new vertex first moves this fraction of its target edge off its partner, along it, as
  /// far as additive CCD clears against everything outside its patch.
  double target_edge_fraction = 0.01;
  /// Failing that, it moves this fraction of the smallest gap at its patch, toward its target
  /// or along random directions (PSQ Alg. 3 line 6 uses 0.01 of the global gap g₀; the local
  /// gap is safe up to 1 and keeps new pairs larger).
  double perturbation = 0.5;
  double close_ratio = 0.999;  ///< ACCD keeps this fraction of a gap below g₀ (Alg. 4)
  double far_ratio = 0.1;      ///< … and this fraction of the others
  /// … and this fraction of the distance of a pair within its offset (new in a split patch:
  /// it must not cross, and opens as the split advances).
  double inside_ratio = 0.1;
  int max_samples = 1024;  ///< directions tried per split before giving up (Alg. 5)
  int max_rounds = 1000;   ///< advancement rounds per batch before every mover stops
  std::uint64_t seed = 1;  ///< of the random directions: results do not depend on threads
};

/// What a refinement did.
struct SafeRefinementStats {
  int batches = 0;
  int splits = 0;
  int random_directions = 0;  ///< splits whose target direction was unsafe (Alg. 5 sampling)
  int rounds = 0;             ///< CCD advancement rounds over all batches
  int stopped_vertices = 0;   ///< movers stopped by contact before their target
  int relaxed_vertices = 0;   ///< stopped movers relaxed locally (PSQ §4.4.3), over all batches
  int relaxation_iterations = 0;  ///< Newton iterations of those relaxations
  /// 1 − Σ‖x̂ − x‖ / Σ‖x̂ − x₀‖ over the movers (x₀ where each started): 1 at the targets.
  double reached = 1.0;
  double min_gap = 0.0;  ///< smallest gap d − ξ of the pairs outside their offsets (m, ≤ d̂)
  /// Pairs left within their contact offset (in patches contact kept from opening): the level's
  /// first solves open them (ContactPotential::fit_offsets, PSQ §4.4.3).
  int inside_pairs = 0;
};

/// Refines `coarse` (|V_level| × 3, intersection-free and outside every contact offset) into
/// level `level + 1` of `hierarchy`, toward `target` (|V_{level+1}| × 3, usually
/// P^l_{l+1}(coarse), PSQ eq. 7). Per batch of hierarchy.expansion_batches[level]: the gap g₀
/// (PSQ §4.4.2), the splits, a perturbation of each new vertex (Algorithm 5: along its target
/// edge as far as CCD allows, else by perturbation × the local gap toward its target or along
/// stratified random directions) until its patch is free of intersections (CGAL exact
/// predicates), then linear advancement of the batch's vertices toward their targets, each
/// round by the largest step additive CCD clears, stopping the vertices of the pairs that bound
/// it (Algorithm 3), and a local relaxation toward their targets of the splits stopped short
/// (§4.4.3, relax_toward_targets). Pairs inside a split patch start closer than their offset;
/// for them CCD keeps them from crossing (offset 0) rather than from coming within ξ.
/// Returns the level-(level+1) positions: free of crossings, though pairs in patches that
/// contact kept from opening may remain within their offsets (counted in the stats).
/// Throws Error(out_of_range) for a bad level, Error(invalid_argument) for mismatched sizes,
/// Error(intersecting) if no safe direction is found for a split.
Positions safe_refinement(const MeshHierarchy& hierarchy, int level, const Positions& coarse,
                          const Positions& target, const RefinementSurroundings& surroundings,
                          const SafeRefinementSettings& settings = {},
                          SafeRefinementStats* stats = nullptr);

}  // namespace progsim
