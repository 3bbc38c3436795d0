#pragma once
/// @file A level's optimisation problem: a sum of energy terms over a DOF vector, some DOFs
/// held fixed (Dirichlet handles). It assembles the reduced gradient and the reduced sparse
/// Hessian the solver needs, with a sparsity pattern built once.
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "energy/energy_term.hpp"
#include "problem/term_stats.hpp"
#include "solve/step_filter.hpp"

namespace progsim {

/// E(x) = Σ_k E_k(x) with fixed DOFs eliminated. Terms are added, then finalize() builds the
/// Hessian pattern; after that every evaluation is allocation-free and OpenMP-parallel.
class Problem {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  /// @param num_dofs 3|V|
  explicit Problem(int num_dofs);

  /// Adds a term (before finalize()) and returns a reference to it. A term that is also a
  /// StepFilter (contact) bounds every Newton step through max_step().
  template <class Term>
  Term& add_term(std::unique_ptr<Term> term) {
    Term& ref = *term;
    add_term_impl(std::move(term));
    return ref;
  }

  /// Marks DOFs as fixed (size num_dofs). Their values come from x; the solver never moves them.
  void set_fixed_dofs(const std::vector<bool>& fixed);

  /// Ties groups of free DOFs together: every DOF of a group moves by the same amount, one
  /// unknown for the group (a rigid support's common translation along one axis). The reduced
  /// problem is then Sᵀ∇E and SᵀHS with S the 0/1 matrix from unknowns to DOFs. Groups are
  /// disjoint and hold no fixed DOF; throws Error(invalid_argument) otherwise.
  void set_shared_dofs(std::vector<std::vector<int>> groups);

  /// Builds the reduced Hessian pattern. Call after the terms and fixed DOFs are set.
  void finalize();

  int num_dofs() const { return num_dofs_; }
  /// Number of unknowns (the size of reduced vectors): free DOFs, a shared group counting once.
  int num_free() const { return static_cast<int>(free_offsets_.size()) - 1; }
  bool is_fixed(int dof) const { return full_to_free_[dof] < 0; }

  /// E(x).
  double value(const Vector& x);
  /// Full gradient ∇E(x) (3|V|) written into g; entries of fixed DOFs are zero.
  void gradient(const Vector& x, Vector& g);
  /// ∇E(x) (3|V|) with the entries of fixed DOFs too (what their supports must supply).
  void unreduced_gradient(const Vector& x, Vector& g);
  /// Reduced Hessian (free × free, lower triangle stored), per-element PSD-projected if asked.
  /// Without terms of changing pattern the reference and its pattern stay valid until the next
  /// finalize(); with them (contact) the pattern may change: see pattern_version().
  const SparseMatrix& hessian(const Vector& x, bool project_psd);

  /// True when every term's hessian_values() is its exact Hessian (EnergyTerm::hessian_is_exact).
  bool hessian_is_exact() const;

  /// Changes whenever the pattern of the matrix hessian() returns changed (so a solver knows
  /// when to redo its symbolic analysis).
  long pattern_version() const { return pattern_version_; }

  /// Forwards to every term's refresh_hessian(): no term reuses an earlier Hessian next time.
  void refresh_hessian();

  /// Forwards to every StepFilter term (see step_filter.hpp); without any: nothing, α = 1.
  /// The Hessian pattern with terms of changing pattern keeps every entry it has held (explicit
  /// zeros), so a contact set that comes and goes keeps the symbolic analysis; a new solve
  /// restarts it from the present entries when they do not fit in it or more than a quarter
  /// of it goes unused.
  void begin_solve(const Vector& x);
  double max_step(const Vector& x, const Vector& p);
  bool end_iteration(const Vector& x);

  /// reduced = Sᵀ full: per unknown, the sum of its DOFs' entries (a gradient's reduction; a
  /// free DOF of no group is its own unknown).
  void restrict_to_free(const Vector& full, Vector& reduced) const;
  /// full = S reduced: each free DOF takes its unknown's value, full[fixed] = 0.
  void expand_from_free(const Vector& reduced, Vector& full) const;

  /// Counters per term, in the order terms were added.
  const std::vector<TermStats>& term_stats() const { return stats_; }
  /// The term with the given name, or nullptr.
  EnergyTerm* find_term(const std::string& name);
  const std::vector<std::unique_ptr<EnergyTerm>>& terms() const { return terms_; }

 private:
  void add_term_impl(std::unique_ptr<EnergyTerm> term);
  void build_reduction();
  void number_unknowns();
  void list_unknown_dofs();
  void build_hessian_pattern();
  const SparseMatrix& add_changing_pattern_terms(const Vector& x, bool project_psd);
  bool locate_triplets_in_combined();
  void grow_combined_pattern();
  bool few_unused_entries();
  void scatter_combined_values();

  int num_dofs_;
  bool finalized_ = false;
  std::vector<bool> fixed_;
  std::vector<std::vector<int>> shared_;
  std::vector<int> full_to_free_;     // the unknown of each DOF, −1 for fixed DOFs
  std::vector<int> free_offsets_{0};  // unknown i's DOFs: free_dofs_[free_offsets_[i] ..]
  std::vector<int> free_dofs_;
  std::vector<std::unique_ptr<EnergyTerm>> terms_;
  std::vector<TermStats> stats_;
  std::vector<std::size_t> entry_offsets_;  // per term, into entry_values_
  std::vector<double> entry_values_;        // all terms' triplet values
  // For each stored nonzero of the reduced Hessian, the triplets summed into it (CSR).
  std::vector<int> nonzero_entry_offsets_;
  std::vector<std::size_t> nonzero_entries_;
  SparseMatrix hessian_;
  // Terms whose pattern changes with x (contact): their reduced triplets, summed with hessian_.
  std::vector<std::size_t> changing_terms_;
  std::vector<StepFilter*> filters_;
  std::vector<Eigen::Triplet<double>> triplets_;
  SparseMatrix changing_part_, combined_;
  bool combined_is_stale_ = true;   // a new solve: combined_'s pattern may be too large
  bool combined_is_built_ = false;  // combined_ and the slots belong to the present hessian_
  std::vector<char> used_;          // few_unused_entries()' marks per entry of combined_
  std::vector<int> hessian_slots_;  // each nonzero of hessian_: its index in combined_
  std::vector<int> triplet_slots_;  // each of triplets_: its index in combined_
  long pattern_version_ = 0;
};

}  // namespace progsim
