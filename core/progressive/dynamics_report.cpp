#include "progressive/dynamics_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/record_json.hpp"

namespace progsim {

DynamicLevelSummary summarize_level(int level, const DynamicLevelRecord& record) {
  DynamicLevelSummary row;
  row.level = level;
  row.vertices = record.vertices;
  row.steps = static_cast<int>(record.steps.size());
  row.seconds = record.seconds;
  row.newton_iterations = record.newton_iterations;
  row.converged_steps = record.converged_steps;
  for (const DynamicStepRecord& s : record.steps) {
    row.max_com_deviation = std::max(row.max_com_deviation, s.com_deviation);
    row.mean_com_deviation += s.com_deviation;
    row.mean_continuity += s.motion.continuity;
    row.max_consistency = std::max(row.max_consistency, s.consistency);
    row.finite = row.finite && std::isfinite(s.motion.kinetic_energy) &&
                 s.motion.center_of_mass.allFinite() && std::isfinite(s.com_deviation);
  }
  if (row.steps > 0) {
    row.mean_com_deviation /= row.steps;
    row.mean_continuity /= row.steps;
  }
  return row;
}

nlohmann::json to_json(const DynamicLevelSummary& r) {
  return {{"level", r.level},
          {"vertices", r.vertices},
          {"steps", r.steps},
          {"wall_seconds", r.seconds},
          {"newton_iterations", r.newton_iterations},
          {"converged_steps", r.converged_steps},
          {"max_com_deviation", r.max_com_deviation},
          {"mean_com_deviation", r.mean_com_deviation},
          {"mean_continuity", r.mean_continuity},
          {"max_consistency", r.max_consistency}};
}

nlohmann::json dynamic_step_json(int level, const DynamicStepRecord& s) {
  nlohmann::json line = {{"level", level},
                         {"step", s.step},
                         {"time", s.time},
                         {"newton_iterations", s.newton_iterations},
                         {"converged", s.converged},
                         {"seconds", s.seconds},
                         {"motion", motion_json(s.motion)},
                         {"com_deviation", s.com_deviation},
                         {"consistency", s.consistency}};
  if (s.contact) line["contact"] = contact_json(*s.contact);
  if (s.max_stretch) line["max_stretch"] = *s.max_stretch;
  if (s.wind) line["wind"] = wind_json(*s.wind);
  if (!s.reactions.empty()) line["reactions"] = reactions_json(s.reactions);
  return line;
}

std::string dynamic_level_table(const std::vector<DynamicLevelSummary>& rows) {
  std::string text =
      "level  vertices  steps  time s  Newton  converged  CoM dev. max m  CoM dev. mean m  "
      "continuity  consistency m\n";
  for (const DynamicLevelSummary& r : rows) {
    char line[200];
    std::snprintf(line, sizeof line,
                  "%5d  %8d  %5d  %6.3g  %6d  %9d  %14.3g  %15.3g  %10.3g  %13.3g\n", r.level,
                  r.vertices, r.steps, r.seconds, r.newton_iterations, r.converged_steps,
                  r.max_com_deviation, r.mean_com_deviation, r.mean_continuity, r.max_consistency);
    text += line;
  }
  return text;
}

const char* prediction_name(DynamicsPrediction prediction) {
  switch (prediction) {
    case DynamicsPrediction::velocity_only:
      return "velocity_only";
    case DynamicsPrediction::prolonged_positions:
      return "prolonged_positions";
    case DynamicsPrediction::per_frame:
      return "per_frame";
  }
  return "velocity_only";
}

}  // namespace progsim
