#pragma once
/// @file Dead point and line loads: fixed forces on vertex groups, each group ramped on its own.
#include <vector>

#include "energy/energy_term.hpp"

namespace progsim {

/// The forces of one load on its vertices (forces fixed in direction and size: a dead load).
struct VertexForces {
  std::vector<int> vertices;  ///< vertex indices into x (|V| numbering), each at most once
  Positions forces;           ///< (|vertices| × 3), N, at full load
};

/// E(x) = −Σ_k s_k Σ_j f_kj · x_{v_kj}: the potential of dead loads (the work of a conservative
/// constant force is −f·x; linear, so the gradient is −s f and there are no Hessian entries).
/// s_k ∈ [0, 1] ramps load k (set_factor), 1 at construction.
class DeadLoads : public EnergyTerm {
 public:
  /// @param loads the loads' full forces; throws Error(invalid_argument) on a vertex outside
  ///        [0, num_vertices) or a forces matrix of the wrong shape
  /// @param num_vertices |V|
  DeadLoads(std::vector<VertexForces> loads, int num_vertices);

  const char* name() const override { return "loads"; }
  double value(const Vector& x) const override;
  void add_gradient(const Vector& x, Vector& g) const override;
  std::size_t hessian_entry_count() const override { return 0; }
  void hessian_pattern(int*, int*) const override {}
  void hessian_values(const Vector&, bool, double*) const override {}

  /// Scales load k (in the order given) by s (1: its full force).
  void set_factor(std::size_t k, double s) { factors_.at(k) = s; }
  /// Replaces load k's full forces (same vertices: |vertices| × 3).
  void set_forces(std::size_t k, const Positions& forces);
  std::size_t num_loads() const { return loads_.size(); }
  /// Σ_k s_k Σ_j f_kj (N): the total force now.
  Vec3 total_force() const;

 private:
  std::vector<VertexForces> loads_;
  std::vector<double> factors_;
};

}  // namespace progsim
