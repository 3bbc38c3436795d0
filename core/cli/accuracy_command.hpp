#pragma once
/// @file `progsim accuracy`: what accuracy costs in time on a scene, progressive against
/// direct at every level (table, CSV and plots).
#include <CLI/CLI.hpp>
#include <string>

namespace progsim::cli {

/// Options of `progsim accuracy SCENE --out DIR [--max-settles N] [--quiet]`.
struct AccuracyCommand {
  std::string scene_path;
  std::string out_dir;
  int max_settles = 500;
  bool quiet = false;
};

/// Registers the subcommand on app; options are written into `options` when parsed.
CLI::App* add_accuracy_command(CLI::App& app, AccuracyCommand& options);

/// Runs the scene progressively and directly, writes the report into the output folder and
/// prints its Markdown table. Throws progsim::Error on bad input.
int run_accuracy_command(const AccuracyCommand& options);

}  // namespace progsim::cli
