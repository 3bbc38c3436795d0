#pragma once
/// @file `progsim accuracy`: what accuracy costs in time on a scene, progressive against
/// direct at every level (table, CSV and plots).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace progsim::cli {

/// Options of `progsim accuracy SCENE --out DIR [--max-settles N] [--direct-levels L ...]
/// [--direct-time-ratio R] [--quiet]`.
struct AccuracyCommand {
  std::string scene_path;
  std::string out_dir;
  int max_settles = 500;
  std::vector<int> direct_levels;  ///< empty: every level
  double direct_time_ratio = 0.0;  ///< 0: direct solves run to the end
  bool of_preview = false;         ///< the ratio multiplies the preview's time, not the pipeline's
  bool quiet = false;
};

/// Registers the subcommand on app; options are written into `options` when parsed.
CLI::App* add_accuracy_command(CLI::App& app, AccuracyCommand& options);

/// Runs the scene progressively and directly, writes the report into the output folder and
/// prints its Markdown table. Throws progsim::Error on bad input.
int run_accuracy_command(const AccuracyCommand& options);

}  // namespace progsim::cli
