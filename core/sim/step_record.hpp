#pragma once
/// @file What one simulation step reports.
#include <string>
#include <vector>

#include "problem/term_stats.hpp"
#include "solve/newton_solver.hpp"

namespace progsim {

/// Report of one step: solver outcome, per-term counters for this step only, wall time.
struct StepRecord {
  int step = 0;                  ///< 1-based index of the step just taken
  double time = 0.0;             ///< simulated time after the step (s)
  NewtonReport newton;           ///< iterations, stop reason, energy, gradient norm, phase timings
  std::vector<TermStats> terms;  ///< counters of each built term during this step
  double seconds = 0.0;          ///< wall time of the whole step
};

/// One line of JSON describing the record (for logs: `steps.jsonl`).
std::string to_json_line(const StepRecord& record);

}  // namespace progsim
