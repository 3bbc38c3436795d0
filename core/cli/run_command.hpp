#pragma once
/// @file `progsim run`: simulate a scene and write meshes, a per-solve log and a summary. A
/// quasistatic scene with a `progressive` section runs as PSQ (preview on the coarsest level,
/// then refinement level by level to the converged finest result), a dynamic one as Progressive
/// Dynamics (dynamics_run.hpp); any other directly.
#include <CLI/CLI.hpp>
#include <string>

#include "cli/run_outcome.hpp"

namespace progsim::cli {

/// Options of `progsim run SCENE --out DIR [--steps N] [--max-settles N] [--direct]
/// [--preview-only] [--quiet]`.
struct RunCommand {
  std::string scene_path;
  std::string out_dir;
  int steps = 0;              ///< load steps; 0: the scene's
  int max_settles = 500;      ///< progressive: solves per level while waiting for equilibrium
  bool direct = false;        ///< solve a progressive scene directly on its finest mesh
  bool preview_only = false;  ///< progressive: stop after level 0's preview, no refinement
  bool quiet = false;
};

/// Registers the subcommand on app; options are written into `options` when parsed.
CLI::App* add_run_command(CLI::App& app, RunCommand& options);

/// Runs the scene and writes its results into the output folder: frame_*.obj (direct: the
/// scene's mesh; progressive: the preview on level 0's own mesh) with obstacles_*.obj beside
/// them (the obstacles as that level's contact met them), prolonged_*.obj (progressive: the
/// preview prolonged to the finest mesh, which may cross), level_*.obj and
/// level_*_obstacles.obj (each level's final state, progressive), steps.jsonl and
/// summary.json; prints the summary. Everything is
/// loaded and validated before the folder is touched. Throws progsim::Error on bad input.
/// Once the run has started, a failure stops it: summary.json, always the last file written,
/// records the outcome ("status": "ok", "not_converged", "failed" or "cancelled", "message",
/// "last_good_step", progressive "last_good_level"). Returns 0 when the run ended "ok",
/// kCancelled after SIGINT, kSimulationFailed otherwise (and says why on stderr).
int run_run_command(const RunCommand& options);

}  // namespace progsim::cli
