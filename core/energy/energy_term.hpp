#pragma once
/// @file The interface every energy term implements. A term knows nothing of levels,
/// prolongation or which DOFs are fixed: the Problem composes terms and reduces.
#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// One additive potential E_k(x) of the incremental potential (DESIGN.md §2).
/// x is the stacked DOF vector (3|V|). Implementations evaluate in parallel (OpenMP) and
/// do not allocate after construction. Not thread-safe: one caller at a time.
class EnergyTerm {
 public:
  virtual ~EnergyTerm() = default;

  /// Stable name used in counters and logs ("membrane", "bending", ...).
  virtual const char* name() const = 0;

  /// E_k(x) (joules).
  virtual double value(const Vector& x) const = 0;

  /// g += ∇E_k(x); g has size 3|V|.
  virtual void add_gradient(const Vector& x, Vector& g) const = 0;

  /// Number of Hessian triplets this term produces; constant over the term's lifetime.
  virtual std::size_t hessian_entry_count() const = 0;

  /// Writes the DOF row and column of each Hessian triplet (called once, at set-up).
  /// Both arrays have hessian_entry_count() entries. Duplicates are summed. Both triangles:
  /// Problem keeps the lower one after reducing, and with shared DOFs (set_shared_dofs) an
  /// entry (i, j) and its mirror (j, i) can land on one reduced diagonal, where both count.
  virtual void hessian_pattern(int* rows, int* cols) const = 0;

  /// Writes the value of each Hessian triplet, in the order of hessian_pattern().
  /// With project_psd every element block is projected to the nearest positive
  /// semi-definite matrix (per-element eigenvalue clamp, projected Newton).
  virtual void hessian_values(const Vector& x, bool project_psd, double* values) const = 0;

  /// False when hessian_values() is a stand-in, not ∇²E_k (the PSQ proxy's level or
  /// Galerkin Hessian): the Newton solver then does not refine its steps against it.
  virtual bool hessian_is_exact() const { return true; }

  /// For terms whose hessian_values() may return an earlier evaluation's matrix (the lazily
  /// refreshed Galerkin Hessian): the next evaluation assembles at its own x. The Newton solver
  /// asks for it when an iteration reduced the gradient too little (a chord method's refresh).
  virtual void refresh_hessian() {}

  /// False for terms whose stencils change with x (contact, friction): the Problem then asks
  /// for their triplets at every Hessian evaluation instead of using a fixed pattern, and
  /// such terms report hessian_entry_count() = 0.
  virtual bool has_fixed_pattern() const { return true; }

  /// Terms without a fixed pattern: appends (row, column, value) triplets of ∇²E_k(x) in full
  /// DOF indices, both triangles (duplicates are summed), element blocks PSD-projected if asked.
  virtual void append_hessian_triplets(const Vector& /*x*/, bool /*project_psd*/,
                                       std::vector<Eigen::Triplet<double>>& /*out*/) const {}
};

}  // namespace progsim
