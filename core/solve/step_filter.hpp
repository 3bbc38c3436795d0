#pragma once
/// @file Terms that restrict which steps a Newton line search may take: continuous collision
/// detection bounds every step so that no configuration ever intersects (IPC, Li et al. 2020,
/// §4.1 "CCD-filtered line search"; C-IPC, Li et al. 2021, §4).
#include "common/types.hpp"

namespace progsim {

/// A step bound consulted by the Newton solver (through the Problem that owns the term).
class StepFilter {
 public:
  virtual ~StepFilter() = default;

  /// Called once at the start of a solve with its starting point x (3|V|).
  virtual void begin_solve(const Vector& x) = 0;

  /// The largest α ∈ [0, 1] for which every point of the segment x + [0, α] p is admissible.
  /// After this call, energies may be evaluated anywhere on that segment (until the next call).
  /// NaN when x + p is not finite: no step is admissible, and the solve stops as non-finite.
  virtual double max_step(const Vector& x, const Vector& p) = 0;

  /// Called after a step was accepted, at the new x. @return true if the objective itself
  /// changed (e.g. an adaptive stiffness grew), so the solver must re-evaluate the energy.
  virtual bool end_iteration(const Vector& x) = 0;
};

}  // namespace progsim
