#include "cli/accuracy_command.hpp"

#include <cstdio>

#include "cli/progress_bar.hpp"
#include "cli/run_command.hpp"
#include "common/error.hpp"
#include "progressive/accuracy.hpp"
#include "progressive/dynamics_accuracy.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"

namespace progsim::cli {

CLI::App* add_accuracy_command(CLI::App& app, AccuracyCommand& options) {
  CLI::App* cmd = app.add_subcommand(
      "accuracy",
      "solve a scene progressively (PSQ; Progressive Dynamics for a dynamic scene) and directly "
      "at every level; write error against time (dynamic: centre-of-mass trajectories) as CSV, "
      "Markdown and PNG plots");
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

namespace {

/// Whether the progressive finest row converged (the truth every error is measured against).
bool finest_converged(const AccuracyReport& report) {
  const AccuracyRow* finest = nullptr;
  for (const AccuracyRow& row : report.rows)
    if (row.method == AccuracyRow::Method::progressive && (!finest || row.level > finest->level))
      finest = &row;
  return finest && finest->converged;
}

/// Errors that say the request itself was bad (exit status 2, as before the run started).
bool bad_input(Status status) {
  return status == Status::invalid_scene || status == Status::invalid_argument ||
         status == Status::invalid_mesh;
}

/// A failure after the start: said on stderr, nothing written; the exit status.
int failed_run(const Error& e) {
  std::fprintf(stderr, "progsim: the accuracy run failed: %s: %s\n", status_name(e.status()),
               e.what());
  return e.status() == Status::cancelled ? kCancelled : kSimulationFailed;
}

/// A dynamic scene: Progressive Dynamics against direct animation at every level.
int run_dynamics_accuracy_command(const Scene& scene, const AccuracyCommand& options) {
  if (!options.direct_levels.empty() || options.direct_time_ratio > 0.0 || options.of_preview)
    fail(Status::invalid_argument,
         "--direct-levels, --direct-time-ratio and --of-preview apply to quasistatic scenes; " +
             scene.name + " is dynamic (every level is animated both ways)");
  ProgressBar bar("accuracy", 100);
  DynamicsAccuracyReport report;
  try {
    report = run_dynamics_accuracy(scene, options.quiet ? nullptr : draw_percent, &bar);
  } catch (const Error& e) {
    if (bad_input(e.status())) throw;
    if (!options.quiet) bar.finish();
    return failed_run(e);
  }
  if (!options.quiet) bar.finish();
  write_dynamics_accuracy_report(report, options.out_dir);
  std::printf("%s", dynamics_accuracy_markdown(report).c_str());
  std::printf(
      "results: %s (accuracy.csv, trajectories.csv, accuracy.md, kinetic_energy.png, "
      "center_of_mass_height.png, com_deviation.png, time_by_level.png)\n",
      options.out_dir.c_str());
  if (finest_levels_converged(report)) return 0;
  std::fprintf(stderr,
               "progsim: the accuracy run did not converge: a finest level has steps short of "
               "the Newton tolerance\n");
  return kSimulationFailed;
}

}  // namespace

int run_accuracy_command(const AccuracyCommand& options) {
  const Scene scene = load_scene_file(options.scene_path);
  check_progressive_scene(scene);  // bad input (status 2) is refused before any work
  if (scene.mode == StepMode::dynamic && scene.progressive.enabled())
    return run_dynamics_accuracy_command(scene, options);
  const DirectSolves direct{
      options.direct_levels, options.direct_time_ratio,
      options.of_preview ? DirectSolves::TimeBase::preview : DirectSolves::TimeBase::pipeline};
  ProgressBar bar("accuracy", 100);
  AccuracyReport report;
  try {
    report = run_accuracy(scene, options.max_settles, options.quiet ? nullptr : draw_percent, &bar,
                          direct);
  } catch (const Error& e) {  // after the start: a failed run, nothing written
    if (bad_input(e.status())) throw;
    if (!options.quiet) bar.finish();
    return failed_run(e);
  }
  if (!options.quiet) bar.finish();
  write_accuracy_report(report, options.out_dir);
  std::printf("%s", accuracy_markdown(report).c_str());
  std::printf(
      "results: %s (accuracy.csv, accuracy.md, error_vs_time.png, error_by_level.png, "
      "time_by_level.png)\n",
      options.out_dir.c_str());
  if (finest_converged(report)) return 0;
  std::fprintf(stderr,
               "progsim: the accuracy run did not converge: the finest level is not at "
               "equilibrium, so its errors are not measured against a converged result "
               "(--max-settles raises the limit)\n");
  return kSimulationFailed;
}

}  // namespace progsim::cli
