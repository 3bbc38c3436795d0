#pragma once
/// @file Totals over a run: where the time went, how Newton behaved, which terms existed.
#include <map>
#include <string>

#include "sim/level_simulation.hpp"
#include "sim/step_record.hpp"

namespace progsim {

/// Accumulates StepRecords and renders a summary (JSON for files, text for terminals).
class RunSummary {
 public:
  void add(const StepRecord& record);

  int steps() const { return steps_; }
  int newton_iterations() const { return iterations_; }
  /// How many steps ended with each stop reason ("converged" → 12, ...).
  const std::map<std::string, int>& stops() const { return stops_; }

  /// Scene, effects, totals, per-phase and per-term time (sim gives the term totals).
  std::string to_json(const LevelSimulation& sim) const;
  /// The same as a short human-readable table.
  std::string to_text(const LevelSimulation& sim) const;

 private:
  int steps_ = 0;
  int iterations_ = 0;
  int max_iterations_ = 0;
  double seconds_ = 0.0;
  double final_energy_ = 0.0;
  double final_gradient_norm_ = 0.0;
  NewtonTimings phases_;
  std::map<std::string, int> stops_;
  std::vector<HandleReaction> final_reactions_;  // the last step's, per handle
};

}  // namespace progsim
