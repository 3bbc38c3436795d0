#pragma once
/// @file Counters of the contact effect: how much broad phase, CCD and barrier work a run did.
#include <cstdint>
#include <limits>

namespace progsim {

/// Cumulative contact counters (a scene without the contact effect has none at all).
struct ContactStats {
  std::int64_t broad_phase_runs = 0;   ///< candidate searches
  std::int64_t candidate_pairs = 0;    ///< sum over searches of the pairs found
  std::int64_t active_pairs = 0;       ///< sum over Hessian assemblies of pairs within d̂
  std::int64_t ccd_calls = 0;          ///< pair CCD queries
  std::int64_t stiffness_updates = 0;  ///< times the adaptive κ grew
  /// Smallest gap d − ξ seen at an accepted configuration (m); +∞ when no pair was within d̂.
  double min_gap = std::numeric_limits<double>::infinity();
  double broad_phase_seconds = 0.0;
  double ccd_seconds = 0.0;
  double assembly_seconds = 0.0;  ///< barrier value, gradient and Hessian evaluation

  /// Counter differences self − before; min_gap is kept (it is the caller's to reset).
  ContactStats since(const ContactStats& before) const {
    ContactStats d = *this;
    d.broad_phase_runs -= before.broad_phase_runs;
    d.candidate_pairs -= before.candidate_pairs;
    d.active_pairs -= before.active_pairs;
    d.ccd_calls -= before.ccd_calls;
    d.stiffness_updates -= before.stiffness_updates;
    d.broad_phase_seconds -= before.broad_phase_seconds;
    d.ccd_seconds -= before.ccd_seconds;
    d.assembly_seconds -= before.assembly_seconds;
    return d;
  }
};

}  // namespace progsim
