#pragma once
/// @file The proxy shell energy of a coarse level (PSQ eq. 2): the finest level's shell
/// potentials evaluated at the prolonged state, Ψ_L(P^l(x_l)), as one energy term of level l.
#include <memory>
#include <vector>

#include "energy/energy_term.hpp"
#include "energy/galerkin_hessian.hpp"
#include "hierarchy/shell_prolongation.hpp"
#include "problem/problem.hpp"

namespace progsim {

/// Ψ_L(P^l(x_l)) (PSQ eqs. 2 and 9). The value is the finest level's; the gradient is exact,
/// J(x)ᵀ ∇Ψ_L(P(x)) with J = U + ∂a/∂x (shell_prolongation.hpp), so a line search on the proxy
/// is a true descent method (PSQ eq. 10 freezes the offset: Uᵀ∇Ψ_L). The Hessian is the
/// level's own shell Hessian ∇²Ψ_l(x_l), a preconditioner as in PSQ Algorithm 1 line 7 that
/// costs O(|V_l|), or the Galerkin product Uᵀ∇²Ψ_L U, which costs a finest-level assembly.
/// Not thread-safe (work buffers); value and gradient are allocation-free after construction.
class ProlongedElastics final : public EnergyTerm {
 public:
  /// `to_finest`: P^l; `finest_terms`: the shell potentials on the finest mesh (3 n_L DOFs);
  /// `level_terms`: the same potentials on level l's mesh (3 n_l DOFs), for the Hessian.
  ProlongedElastics(std::shared_ptr<const ShellProlongation> to_finest,
                    std::vector<std::unique_ptr<EnergyTerm>> finest_terms,
                    std::vector<std::unique_ptr<EnergyTerm>> level_terms);
  /// The same with P = P_L^{L−1} ∘ ⋯ ∘ P_{l+1}^l, the per-level operators composed (coarsest
  /// first in `chain`): smoother than P^l, whose offsets all rotate with one coarse face.
  ProlongedElastics(std::vector<std::shared_ptr<const ShellProlongation>> chain,
                    std::vector<std::unique_ptr<EnergyTerm>> finest_terms,
                    std::vector<std::unique_ptr<EnergyTerm>> level_terms);
  /// The same with the Galerkin Hessian Uᵀ∇²Ψ_L U (galerkin_hessian.hpp) in place of the
  /// level's own; `finest_rest` (n_L × 3) fixes its pattern; it is reassembled once the finest
  /// state has moved more than `refresh_distance` (m; 0: every evaluation), see GalerkinHessian.
  ProlongedElastics(std::vector<std::shared_ptr<const ShellProlongation>> chain,
                    std::vector<std::unique_ptr<EnergyTerm>> finest_terms,
                    const Positions& finest_rest, double refresh_distance = 0.0);

  const char* name() const override { return "prolonged_elastics"; }
  bool hessian_is_exact() const override { return false; }
  double value(const Vector& x) const override;
  void add_gradient(const Vector& x, Vector& g) const override;
  std::size_t hessian_entry_count() const override;
  void hessian_pattern(int* rows, int* cols) const override;
  void hessian_values(const Vector& x, bool project_psd, double* values) const override;
  void refresh_hessian() override;

  /// Holds finest DOFs `dofs` (indices 3v + k) at `values` in place of their prolonged
  /// values: the finest level's handles (Dirichlet conditions, some coordinates of a vertex for
  /// a roller) act exactly, and their gradient is not passed back to the level. Call again when
  /// the handles move.
  void pin_finest_dofs(const std::vector<int>& dofs, const Vector& values);

  /// Counters of the finest-level terms, named "<term>@finest" (how often Ψ_L was evaluated).
  std::vector<TermStats> finest_term_stats() const;
  /// P^l(x) of the last value or gradient evaluation (n_L × 3).
  const Positions& last_prolonged() const { return fine_; }

 private:
  /// Copies x into the coarse buffer and prolongs it into fine_ (and fine_dofs_).
  void prolong(const Vector& x) const;

  std::vector<std::shared_ptr<const ShellProlongation>> chain_;
  std::unique_ptr<Problem> finest_;  // never finalized: value and gradient only
  std::vector<std::unique_ptr<EnergyTerm>> level_terms_;
  std::unique_ptr<GalerkinHessian> galerkin_;  // null: the level terms' Hessian
  std::vector<std::size_t> entry_offsets_;     // per level term, into the Hessian entries
  std::vector<int> pinned_;                    // finest DOFs held at pinned_values_
  Vector pinned_values_;
  // Work buffers (sized once).
  mutable std::vector<Positions> states_;     // input of each operator of the chain
  mutable std::vector<Positions> gradients_;  // gradient w.r.t. each of those inputs
  mutable Positions fine_;
  mutable Vector fine_dofs_, fine_gradient_dofs_;
  mutable std::vector<std::vector<Eigen::Matrix<double, 9, 1>>> workspaces_;  // per operator
};

}  // namespace progsim
