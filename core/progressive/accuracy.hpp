#pragma once
/// @file What accuracy costs in time: a scene solved progressively (PSQ) and directly at every
/// level of its hierarchy, each result compared with the converged finest solution.
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace progsim {

/// One result: a level's state, the wall time it took and its error.
struct AccuracyRow {
  enum class Method { progressive, direct };
  Method method = Method::progressive;
  int level = 0;     ///< 0 = coarsest
  int vertices = 0;  ///< of the level's mesh
  /// Progressive: wall time from the start (after the hierarchy is built) until this level's
  /// equilibrium, the coarser levels and refinements included. Direct: the solve of this level
  /// alone over the whole load script, to equilibrium.
  double seconds = 0.0;
  double refine_seconds = 0.0;  ///< progressive: time spent building this level's start
  int newton_iterations = 0;    ///< on this level (progressive) or in the solve (direct)
  /// Distance of the state, prolonged to the finest mesh, to the converged finest progressive
  /// solution: root mean square and maximum over the finest vertices, divided by the finest
  /// rest shape's bounding-box diagonal.
  double error_rms = 0.0, error_max = 0.0;
  /// Face pairs of the shell and obstacles crossing in the level's final state (CGAL exact).
  int intersecting_pairs = 0;
  /// The level ended at equilibrium (StepRecord::equilibrium), progressive or direct.
  bool converged = false;
  int load_steps = 0;  ///< load steps of the script solved (direct rows stopped early: fewer)
  /// False for a direct solve stopped by DirectSolves::time_ratio: its `seconds` is then only a
  /// lower bound of what the whole solve takes.
  bool finished = true;
};

/// All rows of one scene (progressive levels first, then the direct solves by level).
struct AccuracyReport {
  std::string scene;
  double hierarchy_seconds = 0.0;  ///< building the mesh hierarchy (not in any row's time)
  double diagonal = 0.0;           ///< finest rest bounding-box diagonal (m)
  std::vector<AccuracyRow> rows;
  /// Obstacle vertices each progressive level met (fewer than the scene's where an obstacle is
  /// a progressive collision object, PSQ §4.6); direct solves meet all `obstacle_vertices`.
  std::vector<int> progressive_obstacle_vertices;
  int obstacle_vertices = 0;  ///< the scene's obstacle vertices (0 without contact)
  /// Seconds each direct solve could take (DirectSolves::time_ratio × its base); 0: no limit.
  double direct_time_limit = 0.0;
};

/// Progress of a long run: the fraction of the whole run done and the phase, reported when a
/// phase begins ("progressive level 1", "direct level 0") and after each load step of the
/// preview and of the direct solves ("direct level 2, load step 3 of 20"). Returning false
/// cancels (Error(cancelled)).
using AccuracyProgress = bool (*)(void* user, double fraction, const char* phase);

/// Which levels an accuracy run solves directly, and how long each direct solve may take. On
/// large scenes the direct finest solve can take hours; a time limit still measures a lower
/// bound of the progressive speed-up.
struct DirectSolves {
  std::vector<int> levels;  ///< solved in this order; empty: every level, coarsest first
  /// A direct solve stops within the Newton iteration that takes it past this many times the
  /// progressive time of `time_base` (a load step stopped inside is not counted in
  /// AccuracyRow::load_steps); 0: no limit.
  double time_ratio = 0.0;
  /// What time_ratio multiplies: the progressive time to the converged finest level, or the
  /// coarse preview's (a run that stops once the preview's speed-up is shown to be ≥ ratio).
  enum class TimeBase { pipeline, preview } time_base = TimeBase::pipeline;
};

/// Runs the scene progressively through its load script (preview on level 0 to equilibrium,
/// refinement and equilibrium on each finer level, the finest to convergence) and directly on
/// the levels `direct` names with the same solver settings, also to equilibrium. The scene must
/// ask for coarse levels (Error(invalid_scene) otherwise) and be quasistatic
/// (Error(unsupported)); a direct level that does not exist or a negative time ratio is
/// Error(invalid_argument). Settling stops after `max_settles` solves per level and method.
AccuracyReport run_accuracy(const Scene& scene, int max_settles = 500,
                            AccuracyProgress progress = nullptr, void* user = nullptr,
                            const DirectSolves& direct = {});

/// Writes `accuracy.csv`, `accuracy.md` (table and speed-ups), `error_vs_time.png`,
/// `error_by_level.png` and `time_by_level.png` into `dir` (created). Throws Error(io_error)
/// naming a file that cannot be written.
void write_accuracy_report(const AccuracyReport& report, const std::string& dir);

/// The CSV text: a header line, then one line per row.
std::string accuracy_csv(const AccuracyReport& report);

/// The Markdown text: a table of every row and the measured ratios (coarse preview and full
/// progressive pipeline against the direct finest solve).
std::string accuracy_markdown(const AccuracyReport& report);

}  // namespace progsim
