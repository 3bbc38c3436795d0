#pragma once
/// @file What a progressive (or direct) animation did, level by level: per-step log lines, a
/// per-level summary row (PD Fig. 19's centre-of-mass deviation, PD++'s continuity and
/// consistency) and the table `progsim run` prints.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "progressive/progressive_dynamics.hpp"

namespace progsim {

/// One level of an animation summarised over its steps.
struct DynamicLevelSummary {
  int level = 0;  ///< 0 = coarsest
  int vertices = 0;
  int steps = 0;
  double seconds = 0.0;  ///< wall time of the level's steps
  int newton_iterations = 0;
  int converged_steps = 0;
  /// Max and mean over the steps of the centre-of-mass deviation from the reference trajectory
  /// (progressive: the preview; direct: the direct coarsest level), m.
  double max_com_deviation = 0.0, mean_com_deviation = 0.0;
  double mean_continuity = 0.0;  ///< VPD App. C eq. 18, mean over the steps
  double max_consistency = 0.0;  ///< VPD App. C eq. 19 (m), max over the steps
  bool finite = true;            ///< every step's motion is finite

  /// Every step's Newton solve met the tolerance.
  bool all_converged() const { return converged_steps == steps; }
};

/// The summary of level `level`'s record.
DynamicLevelSummary summarize_level(int level, const DynamicLevelRecord& record);

/// The summary row as JSON (summary.json's "levels").
nlohmann::json to_json(const DynamicLevelSummary& row);

/// One steps.jsonl line: the step tagged with its level; its time, Newton iterations,
/// convergence, wall time, motion (kinetic energy, centre of mass, continuity), centre-of-mass
/// deviation and consistency, and with contact, a strain limit or wind their records (as
/// to_json_line() writes them for a direct step).
nlohmann::json dynamic_step_json(int level, const DynamicStepRecord& step);

/// The rows as a text table: vertices, steps, time, Newton iterations, converged steps and the
/// centre-of-mass deviation (max, mean), continuity and consistency.
std::string dynamic_level_table(const std::vector<DynamicLevelSummary>& rows);

/// "velocity_only", "prolonged_positions" or "per_frame" (the scene file's names).
const char* prediction_name(DynamicsPrediction prediction);

}  // namespace progsim
