#pragma once
/// @file What one simulation step reports.
#include <optional>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "contact/contact_stats.hpp"
#include "problem/term_stats.hpp"
#include "solve/newton_solver.hpp"

namespace progsim {

/// A dynamic step's motion and how continuous it is in time (PD Figs. 18–19; PD++'s metrics as
/// VPD App. C describes them).
struct MotionRecord {
  double kinetic_energy = 0.0;         ///< ½ vᵀ M v after the step (J), level masses
  Vec3 center_of_mass = Vec3::Zero();  ///< Σ m x / Σ m after the step (m)
  /// VPD App. C eq. 17: ‖xᵗ − x̃ᵗ‖_M (m, mass-weighted RMS over the free DOFs), x̃ᵗ the
  /// midpoint estimate of the step's start from its neighbours by implicit Euler as a boundary
  /// value problem, x̃ᵗ = ½(xᵗ⁻¹ + xᵗ⁺¹ − h² M⁻¹ f(xᵗ⁺¹)), with the forces f read from the solve
  /// (h² M⁻¹ f = xᵗ⁺¹ − x̂ − h² M⁻¹ ∇E, x̂ the prediction the step used).
  double continuity_error = 0.0;
  /// eq. 18: continuity_error over the solve's own residual ½h²‖M⁻¹∇E‖_M, floored at the residual
  /// the Newton tolerance allows (½ h ε ℓ): dimensionless, ≤ 1 for implicit Euler on the level
  /// alone, larger where the prediction jumps.
  double continuity = 0.0;
};

/// The wind effect during a step.
struct WindRecord {
  Vec3 velocity = Vec3::Zero();  ///< the wind w the step used (at its end time), m/s
  Vec3 force = Vec3::Zero();     ///< drag and lift on the whole shell after the step (N)
};

/// What one handle's support supplies after a step: R = ∂E/∂x at its prescribed DOFs (E the
/// step's objective, inertia included in dynamic steps: R = M a − f), summed over its vertices.
struct HandleReaction {
  Vec3 force = Vec3::Zero();   ///< Σ R_i (N), zero along the coordinates it leaves free
  Vec3 moment = Vec3::Zero();  ///< Σ (x_i − point) × R_i (N·m)
  Vec3 point = Vec3::Zero();   ///< centroid of the handle's vertices on the level (m)
};

/// Report of one step: solver outcome, per-term counters for this step only, wall time.
struct StepRecord {
  int step = 0;                  ///< 1-based index of the step just taken
  double time = 0.0;             ///< simulated time after the step (s)
  NewtonReport newton;           ///< iterations, stop reason, energy, gradient norm, phase timings
  std::vector<TermStats> terms;  ///< counters of each built term during this step
  double seconds = 0.0;          ///< wall time of the whole step
  /// With the contact effect: this step's contact counters (min_gap: smallest gap this step).
  std::optional<ContactStats> contact;
  /// With friction: contacts frozen for this step's friction (μ > 0 only).
  std::optional<int> friction_contacts;
  /// With the strain-limit effect: the largest membrane stretch after the step.
  std::optional<double> max_stretch;
  /// With the wind effect: the wind and its force.
  std::optional<WindRecord> wind;
  /// With follower loads: how often the step re-aimed them along the normals and solved again.
  std::optional<int> follower_lags;
  /// Fraction of the handles' and obstacles' scripted motion reached this step (1: all; less
  /// when contact kept them from reaching it safely).
  double script_reached = 1.0;
  /// RMS over the vertices of the change this solve made, ‖xᵗ⁺¹ − xᵗ‖₂/√n (m): PSQ
  /// Algorithm 1's d, scripted motion included.
  double change_rms = 0.0;
  /// The state is an equilibrium of the loads (quasistatic scenes), every scripted motion
  /// arrived and every face is back under its own strain limit (raised_limits = 0). A direct solve
  /// (any level) must meet the Newton tolerance; with PSQ eq. 1's proximal term a converged solve
  /// is only a gradient-flow step, so there the tolerance must hold before any Newton step. A
  /// preview (proxy) solve, capped at a few iterations, stops stepping once its change is below the
  /// tolerance: ‖d‖₂ < √n_l h ε (PSQ §4.5, Algorithm 1 line 10, with h = 1 and ε = tolerance × the
  /// scene's length).
  bool equilibrium = false;
  /// Contact pairs whose offset is still lowered after a refinement that left them within
  /// their offsets (PSQ §4.4.3 relaxation by offset homotopy); 0 once the full offsets hold.
  int reduced_offsets = 0;
  /// Faces whose strain limit is still raised after a refinement that left them beyond it
  /// (StrainLimit::fit_limits); 0 once every face's own limit holds.
  int raised_limits = 0;
  /// Dynamic scenes: the motion after the step.
  std::optional<MotionRecord> motion;
  /// Per scene handle, the force and moment its support applies; empty without handles and on
  /// preview levels (the proxy holds the finest handle vertices and passes no force back).
  std::vector<HandleReaction> reactions;
};

/// One line of JSON describing the record (for logs: `steps.jsonl`).
std::string to_json_line(const StepRecord& record);

}  // namespace progsim
