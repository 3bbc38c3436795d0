#pragma once
/// @file Follower loads: forces along the surface normal, re-aimed at the lagged state.
#include <vector>

#include "energy/dead_loads.hpp"

namespace progsim {

/// A load along the normal: each vertex's force is its magnitude times its unit normal.
struct NormalLoad {
  std::vector<int> vertices;   ///< vertex indices into x (|V| numbering), each at most once
  Eigen::VectorXd magnitudes;  ///< N at full load, along the normal (|vertices|)
};

/// E(x) = −Σ_k s_k Σ_j a_kj n_kj · x_{v_kj}: forces a n along directions n aimed at each vertex's
/// unit normal n̄(x) (the area-weighted mean of its faces' normals) at a lagged state, like
/// IPC's lagged friction (Li et al. 2020, §5): within a solve a dead load, whose potential
/// exists. Solving again after relax() until the directions stop turning (LevelSimulation)
/// ends at a state in equilibrium with the forces along its own normals: the follower load.
class FollowerLoads : public EnergyTerm {
 public:
  /// @param loads one per scene load (empty for loads without a normal force); throws
  ///        Error(invalid_argument) like DeadLoads
  /// @param faces the faces whose normals the load vertices take
  FollowerLoads(std::vector<NormalLoad> loads, const Faces& faces, int num_vertices);

  const char* name() const override { return "follower_loads"; }
  double value(const Vector& x) const override { return aimed_.value(x); }
  void add_gradient(const Vector& x, Vector& g) const override { aimed_.add_gradient(x, g); }
  std::size_t hessian_entry_count() const override { return 0; }
  void hessian_pattern(int*, int*) const override {}
  void hessian_values(const Vector&, bool, double*) const override {}

  /// Aims every force along n̄(x) (a new step's start). Returns the largest angle (rad) between
  /// a new and the previous direction (π at the first call).
  double aim(const Vector& x);

  /// Turns the directions toward n̄(x) by Aitken's dynamic relaxation of the fixed point
  /// n = n̄(x(n)) (Irons and Tuck 1969; Küttler and Wall 2008, eq. 44): the plain step first,
  /// then n += ω (n̄ − n) with ω = −ω_prev r_prevᵀ(r − r_prev) / ‖r − r_prev‖², r = n̄ − n, which
  /// converges where plain lagging diverges (a cantilever's end load at P L² / E I = 4).
  /// Returns the largest angle (rad) between n̄(x) and the directions before the call, and
  /// changes nothing when it is at most `settled` (the forces x was solved for stay).
  double relax(const Vector& x, double settled);

  /// Scales load k by s (1: its full force), as DeadLoads::set_factor.
  void set_factor(std::size_t k, double s) { aimed_.set_factor(k, s); }

 private:
  /// n̄(x) of every loaded vertex, stacked (3 per vertex, loads in order), into target_.
  void measure_normals(const Vector& x);
  /// Largest angle between the 3-blocks of directions_ and target_ (rad).
  double largest_turn() const;
  /// The forces a n from directions_.
  void aim_forces();

  std::vector<NormalLoad> loads_;
  std::vector<std::vector<int>> vertex_faces_;  // per loaded vertex (stacked): its faces
  Faces faces_;
  Vector directions_, target_, residual_, previous_residual_, change_;  // stacked 3-blocks
  std::vector<Positions> forces_;  // per load: the forces a n aim_forces() hands to aimed_
  double omega_ = 1.0;             // Aitken's relaxation factor
  bool lagged_ = false, have_residual_ = false;
  DeadLoads aimed_;  // the forces a n of the current directions
};

}  // namespace progsim
