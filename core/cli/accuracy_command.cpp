#include "cli/accuracy_command.hpp"

#include <cstdio>

#include "cli/progress_bar.hpp"
#include "progressive/accuracy.hpp"
#include "scene/scene_json.hpp"

namespace progsim::cli {

CLI::App* add_accuracy_command(CLI::App& app, AccuracyCommand& options) {
  CLI::App* cmd = app.add_subcommand(
      "accuracy",
      "solve a scene progressively (PSQ) and directly at every level; write error "
      "against time as CSV, Markdown and PNG plots");
  cmd->add_option("scene", options.scene_path, "scene file (JSON) with a 'progressive' section")
      ->required();
  cmd->add_option("--out", options.out_dir, "output folder (created)")->required();
  cmd->add_option("--max-settles", options.max_settles,
                  "solves per level while waiting for equilibrium")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--direct-levels", options.direct_levels,
                  "levels to solve directly (default: all; 0 = coarsest)");
  cmd->add_option("--direct-time-ratio", options.direct_time_ratio,
                  "stop each direct solve once it has taken this many times the progressive "
                  "time; its ratios are then lower bounds (default 0: no limit)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--of-preview", options.of_preview,
                "--direct-time-ratio multiplies the coarse preview's time, not the pipeline's: "
                "the run stops once the preview is shown that many times faster");
  cmd->add_flag("--quiet", options.quiet, "no progress bar");
  return cmd;
}

int run_accuracy_command(const AccuracyCommand& options) {
  const Scene scene = load_scene_file(options.scene_path);
  const DirectSolves direct{
      options.direct_levels, options.direct_time_ratio,
      options.of_preview ? DirectSolves::TimeBase::preview : DirectSolves::TimeBase::pipeline};
  ProgressBar bar("accuracy", 100);
  const AccuracyReport report = run_accuracy(scene, options.max_settles,
                                             options.quiet ? nullptr : draw_percent, &bar, direct);
  if (!options.quiet) bar.finish();
  write_accuracy_report(report, options.out_dir);
  std::printf("%s", accuracy_markdown(report).c_str());
  std::printf(
      "results: %s (accuracy.csv, accuracy.md, error_vs_time.png, error_by_level.png, "
      "time_by_level.png)\n",
      options.out_dir.c_str());
  return 0;
}

}  // namespace progsim::cli
