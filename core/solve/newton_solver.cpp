#include "solve/newton_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "common/thread_budget.hpp"
#include "common/timer.hpp"
#include "solve/truncated_newton.hpp"

namespace progsim {

const char* stop_name(NewtonStop stop) {
  switch (stop) {
    case NewtonStop::converged:
      return "converged";
    case NewtonStop::max_iterations:
      return "max_iterations";
    case NewtonStop::line_search_failed:
      return "line_search_failed";
    case NewtonStop::non_finite:
      return "non_finite";
    case NewtonStop::factorization_failed:
      return "factorization_failed";
    case NewtonStop::interrupted:
      return "interrupted";
  }
  return "unknown";
}

namespace {

/// CG's trust region in units of the projected step: its start, its growth after a refined
/// step the line search took whole (Nocedal & Wright 2006, Algorithm 4.1's doubling) and its
/// cap. Starting at 4 rather than 1 saved a fifth of the Newton iterations of a short
/// twisted-cloth run (16 × 16 cells, 6 steps) without longer line searches.
constexpr double kInitialRadius = 4.0;
constexpr double kRadiusGrowth = 2.0;
constexpr double kMaxRadius = 1e4;

/// The next trust-region radius from how the line search took a refined step: doubled after
/// a whole step that reached the boundary, shrunk to the length taken after a cut one (never
/// below the projected step's), else kept. An extrapolated step (α > 1) counts as a whole one:
/// the radius bounds the model's step, extrapolation measures the energy's.
double next_radius(double radius, const TruncatedNewtonStats& cg, double alpha) {
  if (alpha < 1.0) return std::max(1.0, alpha * cg.length);
  return cg.on_boundary ? std::min(kRadiusGrowth * radius, kMaxRadius) : radius;
}

/// Extrapolation starts when a whole step's energy drop exceeds this multiple of the Newton
/// model's, ½|gᵀp| for Hp = −g (Nocedal & Wright eq. 4.4's ratio ρ): then the parabola through
/// E(0), E'(0) = gᵀp and E(1) has its minimum beyond α = 2, at 1 / (2 − ρ), or has none.
constexpr double kExtrapolationRatio = 1.5;
/// Doublings of α at most (α ≤ 1024) per step.
constexpr int kMaxDoublings = 10;

/// A step the line search refused is retried shortened to this fraction of the scene's
/// length (capped_line_search).
constexpr double kFallbackStepFraction = 0.1;

/// A term that reuses an earlier Hessian (EnergyTerm::refresh_hessian) reassembles once a
/// Newton step is longer than this fraction of the previous one: a chord method contracting
/// slower than that pays for a fresh matrix (Kelley 2003, §2.3, Shamanskii's method with the
/// refresh chosen by the observed contraction). On the 8.6K-vertex drape (30 preview steps)
/// 0.5 assembled 91 times, 0.8 45 times and never 30 times for 261–264 Newton iterations; on
/// a flexing cloth in wind never refreshing left 9 of 10 steps unconverged.
constexpr double kChordContraction = 0.8;

/// A refused step whose predicted decrease ½|gᵀp| is below this many ulps of |E| leaves nothing
/// the energy can resolve: the solve has converged to working precision. A stiff strip (E t =
/// 10⁶ N/m, tolerance 1e-9) stalled at a step 1.001 times the tolerance with gᵀp = −2e-19 J
/// against E = −0.05 J, every halving refused by rounding.
constexpr double kRoundingUlps = 16.0;

/// Whether a Newton step's predicted decrease is below the rounding of the energy.
bool below_rounding(double slope, double energy) {
  return -0.5 * slope <= kRoundingUlps * std::numeric_limits<double>::epsilon() * std::abs(energy);
}

}  // namespace

/// Doubles a whole step's α while the energy keeps falling and the step filters (CCD) admit
/// the longer segment; a refused segment is followed by a call for the accepted one, after which
/// the filters again admit energies there (step_filter.hpp). @return true if it lengthened the
/// step (trial_ is its end point).
bool NewtonSolver::extrapolate(Problem& problem, const Vector& x, double energy, double slope,
                               double& alpha, double& new_energy) {
  if (!(slope < 0.0) || (new_energy - energy) / (0.5 * slope) <= kExtrapolationRatio) return false;
  bool longer = false;
  for (int k = 0; k < kMaxDoublings; ++k) {
    longer_step_ = (2.0 * alpha) * step_;
    if (!(problem.max_step(x, longer_step_) >= 1.0)) {  // refused, or NaN
      longer_step_ = alpha * step_;
      problem.max_step(x, longer_step_);  // admitted before: re-establishes the filters' state
      break;
    }
    longer_trial_ = x + longer_step_;
    const double e = problem.value(longer_trial_);
    if (!(e < new_energy)) break;  // also stops on NaN or +inf (a barrier was crossed)
    alpha *= 2.0;
    new_energy = e;
    trial_.swap(longer_trial_);
    longer = true;
  }
  return longer;
}

bool NewtonSolver::line_search(Problem& problem, const Vector& x, double energy, double slope,
                               const NewtonSettings& settings, double& alpha, double& new_energy) {
  alpha = problem.max_step(x, step_);  // CCD bound: no step may let primitives cross
  for (int k = 0; k < settings.max_backtracks && alpha > 0.0; ++k, alpha *= 0.5) {
    trial_ = x + alpha * step_;
    new_energy = problem.value(trial_);
    if (std::isfinite(new_energy) && new_energy <= energy + settings.armijo * alpha * slope)
      return true;  // Armijo condition
  }
  return false;
}

/// Retries a failed line search with the step shortened to kFallbackStepFraction of the
/// scene's length. A Hessian that is singular along a mechanism (a sheet hinged on one line of
/// handles: rotating about the line costs no elastic energy, and quasistatics has no inertia)
/// factorizes with a tiny pivot and gives a step of ~1e15 m that 40 halvings cannot bring back
/// to the scene; its direction is still a descent direction for a PSD Hessian (gᵀH⁻¹g > 0), and
/// along a mechanism it is the motion the load drives. Steps a line search accepts are never
/// shortened, so converging solves are unchanged. @return true if the shortened step was taken.
bool NewtonSolver::capped_line_search(Problem& problem, const Vector& x, double energy,
                                      const NewtonSettings& settings, double length, double& alpha,
                                      double& new_energy, NewtonReport& report) {
  const double cap = kFallbackStepFraction * length;
  if (!(report.step_norm > cap) || !std::isfinite(report.step_norm)) return false;
  const double scale = cap / report.step_norm;
  step_ *= scale;
  step_free_ *= scale;
  report.step_norm = cap;
  const double slope = gradient_free_.dot(step_free_);
  if (!(slope < 0.0)) return false;
  ++report.capped_steps;
  return line_search(problem, x, energy, slope, settings, alpha, new_energy);
}

void NewtonSolver::analyze_if_needed(const Problem& problem, const Problem::SparseMatrix& h,
                                     NewtonReport& report) {
  if (analyzed_for_ == &problem && analyzed_version_ == problem.pattern_version()) return;
  ScopedTimer timer(report.timings.analysis);
  cholesky_.analyze(h);
  ++report.symbolic_analyses;
  analyzed_for_ = &problem;
  analyzed_version_ = problem.pattern_version();
}

/// Assembles and factorizes the Hessian of this iteration per the projection policy; with
/// `keep_exact`, an iteration that ends up projecting keeps the exact Hessian in exact_.
/// @return false when CHOLMOD failed even with a shift.
bool NewtonSolver::factorize_hessian(Problem& problem, const Vector& x,
                                     HessianProjection projection, bool try_exact, bool keep_exact,
                                     NewtonReport& report) {
  NewtonTimings& time = report.timings;
  if (projection != HessianProjection::always && (try_exact || keep_exact)) {
    const Problem::SparseMatrix* exact = nullptr;
    {
      ScopedTimer timer(time.assembly);
      exact = &problem.hessian(x, false);
    }
    analyze_if_needed(problem, *exact, report);
    if (try_exact) {
      ScopedTimer timer(time.factorization);
      if (cholesky_.factorize(*exact, projection == HessianProjection::never)) {
        ++report.exact_steps;
        report.max_shift = std::max(report.max_shift, cholesky_.shift());
        return true;
      }
      if (projection == HessianProjection::never) return false;
    }
    if (keep_exact) {
      ScopedTimer timer(time.assembly);
      exact_ = *exact;  // the next hessian() call overwrites *exact
    }
  }
  const Problem::SparseMatrix* projected = nullptr;
  {
    ScopedTimer timer(time.assembly);
    projected = &problem.hessian(x, true);
  }
  analyze_if_needed(problem, *projected, report);
  ScopedTimer timer(time.factorization);
  if (!cholesky_.factorize(*projected)) return false;
  report.max_shift = std::max(report.max_shift, cholesky_.shift());
  return true;
}

std::optional<TruncatedNewtonStats> NewtonSolver::solve_step(bool refine, int max_cg_iterations,
                                                             double radius, NewtonReport& report) {
  ScopedTimer timer(report.timings.solve);
  if (!refine) {
    cholesky_.solve(-gradient_free_, step_free_);
    return std::nullopt;
  }
  TruncatedNewtonSettings cg_settings;
  cg_settings.max_iterations = max_cg_iterations;
  cg_settings.radius = radius;
  const TruncatedNewtonStats cg =
      truncated_newton_step(exact_, cholesky_, gradient_free_, cg_settings, step_free_, cg_work_);
  report.cg_iterations += cg.iterations;
  return cg;
}

NewtonReport NewtonSolver::minimize(Problem& problem, Vector& x, const NewtonSettings& settings,
                                    double decrement_scale, double length) {
  NewtonReport report;
  NewtonTimings& time = report.timings;
  problem.begin_solve(x);
  longer_step_.resize(x.size());  // extrapolation's buffers, sized once
  longer_trial_.resize(x.size());
  double energy = problem.value(x);
  // Solves whose first exact attempts keep failing (a hanging cloth: compressed, indefinite)
  // stop paying for them; every 8th solve probes again.
  // The unprojected Hessian is tried only where it is the energy's (or always asked for): a
  // stand-in (the PSQ proxy's) only preconditions, its unprojected steps are no Newton steps.
  const bool unprojected_allowed =
      problem.hessian_is_exact() || settings.projection == HessianProjection::never;
  bool try_exact = unprojected_allowed && (exact_failure_streak_ < 3 || solves_ % 8 == 0);
  ++solves_;
  double cg_radius = kInitialRadius;  // CG's trust region, per solve
  int failed_exact = 0;               // an indefinite problem (e.g. pressure) stops trying after 3
  // Projected steps are refined against the exact Hessian only where it is the energy's.
  const bool refine_projected = settings.projection == HessianProjection::adaptive &&
                                settings.max_cg_iterations > 0 && problem.hessian_is_exact();
  for (report.iterations = 0; report.iterations < settings.max_iterations; ++report.iterations) {
    refresh_thread_budget();  // the team size follows the machine's load (thread_budget.hpp)
    if (interrupted_ && interrupted_()) {
      report.stop = NewtonStop::interrupted;
      break;
    }
    {
      ScopedTimer timer(time.assembly);
      problem.gradient(x, gradient_);
      problem.restrict_to_free(gradient_, gradient_free_);
    }
    report.gradient_norm = gradient_free_.norm();
    if (!std::isfinite(energy) || !std::isfinite(report.gradient_norm)) {
      report.stop = NewtonStop::non_finite;
      break;
    }

    const int exact_before = report.exact_steps;
    if (!factorize_hessian(problem, x, settings.projection, try_exact, refine_projected, report)) {
      report.stop = NewtonStop::factorization_failed;
      break;
    }
    if (try_exact)
      exact_failure_streak_ = report.exact_steps == exact_before ? exact_failure_streak_ + 1 : 0;
    if (try_exact && report.exact_steps == exact_before) {
      try_exact = false;
      ++failed_exact;
    }
    const std::optional<TruncatedNewtonStats> cg =
        solve_step(refine_projected && report.exact_steps == exact_before,
                   settings.max_cg_iterations, cg_radius, report);
    problem.expand_from_free(step_free_, step_);
    const double previous_step = report.step_norm;
    report.step_norm = step_.lpNorm<Eigen::Infinity>();
    if (report.iterations > 0 && report.step_norm > kChordContraction * previous_step)
      problem.refresh_hessian();
    if (!std::isfinite(report.step_norm)) {
      report.stop = NewtonStop::non_finite;
      break;
    }
    if (report.step_norm / decrement_scale < settings.tolerance * length) {  // C-IPC stop rule
      report.stop = NewtonStop::converged;
      break;
    }
    ScopedTimer timer(time.line_search);
    double alpha = 1.0, new_energy = energy;
    const double slope = gradient_free_.dot(step_free_);
    const bool accepted = line_search(problem, x, energy, slope, settings, alpha, new_energy);
    if (std::isnan(alpha)) {  // the CCD bound of a non-finite motion (StepFilter::max_step)
      report.stop = NewtonStop::non_finite;
      break;
    }
    if (!accepted &&
        !capped_line_search(problem, x, energy, settings, length, alpha, new_energy, report)) {
      report.stop =
          below_rounding(slope, energy) ? NewtonStop::converged : NewtonStop::line_search_failed;
      break;
    }
    if (alpha == 1.0 && settings.extrapolate &&
        extrapolate(problem, x, energy, slope, alpha, new_energy))
      ++report.extrapolated_steps;
    if (cg) cg_radius = next_radius(cg_radius, *cg, alpha);
    if (alpha >= 1.0 && failed_exact < 3 && unprojected_allowed) try_exact = true;
    x = trial_;
    energy = new_energy;
    if (problem.end_iteration(x)) energy = problem.value(x);  // e.g. contact stiffness grew
  }
  // Report the state actually returned.
  if (report.stop == NewtonStop::max_iterations || report.stop == NewtonStop::interrupted) {
    ScopedTimer timer(time.assembly);
    problem.gradient(x, gradient_);
    problem.restrict_to_free(gradient_, gradient_free_);
    report.gradient_norm = gradient_free_.norm();
  }
  report.energy = energy;
  return report;
}

}  // namespace progsim
