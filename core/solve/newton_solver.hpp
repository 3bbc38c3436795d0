#pragma once
/// @file Projected Newton with backtracking line search (DESIGN.md §2; C-IPC, Li et al. 2021).
#include <functional>
#include <optional>

#include "problem/problem.hpp"
#include "solve/sparse_cholesky.hpp"
#include "solve/truncated_newton.hpp"

namespace progsim {

/// Which Hessian a Newton iteration factorizes.
enum class HessianProjection {
  /// Always the per-element PSD-projected Hessian (projected Newton, Teran et al. 2005).
  always,
  /// The exact Hessian whenever CHOLMOD factorizes it without a shift (then it is positive
  /// definite and gives a true Newton step), else the projected one. With max_cg_iterations
  /// > 0, a projected step is then refined by CG against the exact Hessian when the
  /// problem's Hessian is exact (truncated_newton.hpp): it follows the curvature projection
  /// discarded, e.g. of folds and twists, stops at negative curvature, and stays in a trust
  /// region that starts at four times the projected step's length and doubles while refined
  /// steps are taken whole (it shrinks to what the line search took otherwise). After a
  /// failed exact attempt, the exact Hessian is tried again only once a full step (α = 1) was
  /// accepted, and not at all after three failures in one solve; after three failed attempts
  /// in a row (across solves, e.g. every step of a hanging cloth) only every 8th solve tries.
  /// Projection discards the geometric stiffness of bent hinges; near a bent equilibrium
  /// (stiff thin strips) exact steps converge in far fewer iterations (Longva et al. 2023).
  /// Only where the problem's Hessian is exact (Problem::hessian_is_exact): a stand-in Hessian
  /// (the PSQ proxy's) is always projected. Unprojected, its steps are no Newton steps of the
  /// proxy energy: on a perturbed twist, level 1's solves took them at α = 2⁻¹⁰, 500 solves
  /// in a row.
  adaptive,
  /// Always the exact Hessian (shifted when indefinite); for tests and comparison.
  never,
};

/// Settings of one Newton solve.
struct NewtonSettings {
  /// Stop when ‖p‖∞ / scale < tolerance · length (Newton decrement, C-IPC §6); scale is h
  /// for dynamics (velocity units) and 1 for quasistatics; length is the scene's size.
  double tolerance = 1e-5;
  int max_iterations = 100;                                    ///< iteration cap
  HessianProjection projection = HessianProjection::adaptive;  ///< see HessianProjection
  double armijo = 1e-4;     ///< sufficient-decrease constant c in E(x+αp) ≤ E + cα gᵀp
  int max_backtracks = 40;  ///< halvings of α before the line search gives up
  /// Adaptive projection: CG iterations refining a projected step against the exact Hessian
  /// (truncated_newton.hpp); 0 (the default) takes projected steps as they are. Opt-in
  /// because it pays off on some scenes only (bench_newton_refinement, one run each, before
  /// line-search extrapolation below): the twisted cloth at 1089 vertices 1.55× faster (908
  /// against 1538 iterations), at 4225 vertices no faster (1494 against 1730 iterations, each
  /// dearer by an exact Hessian), the crushed can at 1800 vertices 1.27× slower (5666 against
  /// 4921 iterations).
  int max_cg_iterations = 0;
  /// Lengthen a whole step (α = 1) whose energy fell much more than the quadratic model
  /// predicted, by doubling α while the energy keeps falling and CCD allows (line-search
  /// extrapolation, Nocedal & Wright 2006 §3.5). Projection overstates the curvature of a
  /// shell leaving a flat or buckling state, so its steps are too short there. The twist at
  /// 1089 vertices took 975 Newton iterations with it, 1538 without, 1.50× faster (19 against
  /// 10 of 20 steps converged; bench/results/newton_refinement.csv); one `progsim run --direct`
  /// each: the crushed can 3691 against 4921, the balloon 64 against 141. False for tests and
  /// comparison.
  bool extrapolate = true;
};

/// Why a Newton solve stopped.
enum class NewtonStop {
  /// the decrement fell below the tolerance, or a refused step predicted a decrease the
  /// energy's rounding cannot resolve (under 16 ulps of |E|)
  converged,
  max_iterations,        ///< the iteration cap was reached first
  line_search_failed,    ///< no step length decreased the energy
  non_finite,            ///< the energy, gradient, step or its CCD bound became NaN/Inf
  factorization_failed,  ///< CHOLMOD failed even with a diagonal shift
  interrupted,           ///< the solver's interrupt check asked to stop (set_interrupt)
};

/// Stable name of a stop reason ("converged", ...).
const char* stop_name(NewtonStop stop);

/// Seconds spent in each phase of a solve.
struct NewtonTimings {
  double assembly = 0.0;       ///< gradient + Hessian evaluation and reduction
  double analysis = 0.0;       ///< CHOLMOD symbolic analyses (one per new Hessian pattern)
  double factorization = 0.0;  ///< CHOLMOD numeric factorization (with retries)
  double solve = 0.0;          ///< triangular solves
  double line_search = 0.0;    ///< energy evaluations while backtracking
  NewtonTimings& operator+=(const NewtonTimings& o) {
    assembly += o.assembly, analysis += o.analysis, factorization += o.factorization;
    solve += o.solve, line_search += o.line_search;
    return *this;
  }
};

/// Outcome of a Newton solve.
struct NewtonReport {
  int iterations = 0;
  NewtonStop stop = NewtonStop::max_iterations;
  double energy = 0.0;         ///< E at the returned x (J)
  double gradient_norm = 0.0;  ///< ‖∇E‖₂ over free DOFs at the returned x
  double step_norm = 0.0;      ///< ‖p‖∞ of the last Newton direction (m)
  double max_shift = 0.0;      ///< largest diagonal shift CHOLMOD needed
  int exact_steps = 0;         ///< iterations that used the exact (unprojected) Hessian
  int cg_iterations = 0;       ///< CG iterations refining projected steps (truncated_newton)
  int extrapolated_steps = 0;  ///< whole steps the line search lengthened (extrapolate)
  int capped_steps = 0;        ///< refused steps retried shortened (a mechanism, e.g. a hinge)
  /// CHOLMOD symbolic analyses (orderings): one per new Hessian pattern, e.g. a contact-set
  /// change; every other iteration only refactorizes numerically.
  int symbolic_analyses = 0;
  NewtonTimings timings;
};

/// Projected Newton minimiser. Keeps the factorization's symbolic analysis and all work
/// vectors between solves, so repeated solves on one Problem do not allocate.
class NewtonSolver {
 public:
  /// Minimises problem's energy from x (3|V|, fixed DOFs already at their targets), in place.
  /// @param decrement_scale h for dynamics, 1 for quasistatics
  /// @param length characteristic length of the scene (m), e.g. bounding-box diagonal
  NewtonReport minimize(Problem& problem, Vector& x, const NewtonSettings& settings,
                        double decrement_scale, double length);

  /// A check every later solve makes before each iteration: when it returns true the solve
  /// stops (NewtonStop::interrupted) at its last accepted iterate, as intersection-free as any
  /// other (each accepted step passed CCD). Empty (the default): solves are never interrupted.
  void set_interrupt(std::function<bool()> interrupted) { interrupted_ = std::move(interrupted); }

 private:
  bool line_search(Problem& problem, const Vector& x, double energy, double slope,
                   const NewtonSettings& settings, double& alpha, double& new_energy);
  bool extrapolate(Problem& problem, const Vector& x, double energy, double slope, double& alpha,
                   double& new_energy);
  bool capped_line_search(Problem& problem, const Vector& x, double energy,
                          const NewtonSettings& settings, double length, double& alpha,
                          double& new_energy, NewtonReport& report);

  SparseCholesky cholesky_;
  const Problem* analyzed_for_ = nullptr;
  long analyzed_version_ = -1;
  int exact_failure_streak_ = 0;  ///< consecutive failed exact attempts, across solves
  long solves_ = 0;
  void analyze_if_needed(const Problem& problem, const Problem::SparseMatrix& h,
                         NewtonReport& report);
  bool factorize_hessian(Problem& problem, const Vector& x, HessianProjection projection,
                         bool try_exact, bool keep_exact, NewtonReport& report);
  /// The step of this iteration from the factorized Hessian into step_free_; a projected one
  /// refined against exact_ when `refine`.
  std::optional<TruncatedNewtonStats> solve_step(bool refine, int max_cg_iterations, double radius,
                                                 NewtonReport& report);

  Vector gradient_, gradient_free_, step_free_, step_, trial_, longer_step_, longer_trial_;
  Problem::SparseMatrix exact_;  ///< the exact Hessian of an iteration that projected
  Vector cg_work_[4];
  std::function<bool()> interrupted_;
};

}  // namespace progsim
