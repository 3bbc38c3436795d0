#include "cli/run_command.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "cli/dynamics_run.hpp"
#include "cli/progress_bar.hpp"
#include "cli/run_outcome.hpp"
#include "cli/run_output.hpp"
#include "common/error.hpp"
#include "common/timer.hpp"
#include "mesh/mesh_io.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "sim/level_simulation.hpp"
#include "sim/record_json.hpp"
#include "sim/run_summary.hpp"

namespace fs = std::filesystem;

namespace progsim::cli {
namespace {

int run_direct(Scene scene, const RunCommand& opt) {
  LevelSimulation sim(std::move(scene));
  sim.set_interrupt(interrupted);  // a long solve stops at its iterate
  const int steps = opt.steps > 0 ? opt.steps : sim.scene().num_steps();
  const fs::path dir(opt.out_dir);
  std::ofstream log = open_log(dir);
  const auto write_frame = [&](int frame) {
    write_mesh(numbered(dir, "frame_", frame),
               TriangleMesh{sim.positions(), sim.model().rest.faces});
    write_nonempty(numbered(dir, "obstacles_", frame), met_obstacles(sim));
  };
  RunSummary summary;
  Outcome outcome;
  ProgressBar bar(sim.scene().name, steps);
  std::optional<StepRecord> last;
  int step = 0;  // the step being taken (0: writing the start)
  try {
    write_frame(0);
    for (step = 1; step <= steps; ++step) {
      stop_if_interrupted();
      last = sim.step();
      log << to_json_line(*last) << "\n";
      summary.add(*last);
      if (const auto why = solve_failure(*last, sim.positions())) {
        outcome.fail("step " + std::to_string(step) + ": " + *why);
        break;
      }
      if (last->newton.stop == NewtonStop::converged) outcome.last_good_step = step;
      if (step % sim.scene().output_every == 0 || step == steps) write_frame(step);
      if (!opt.quiet) bar.update(step);
    }
  } catch (const Error& e) {
    outcome.fail("step " + std::to_string(step), e);
  }
  if (!opt.quiet) bar.finish();
  if (outcome.ok() && last && last->newton.stop != NewtonStop::converged) {
    outcome.status = "not_converged";
    char why[256];
    std::snprintf(why, sizeof why,
                  "the last step (%d) ended '%s' after %d Newton iterations with gradient norm "
                  "%.3g; its state is not an equilibrium",
                  last->step, stop_name(last->newton.stop), last->newton.iterations,
                  last->newton.gradient_norm);
    outcome.message = why;
  }
  log.close();  // flushed before the summary, which is written last
  nlohmann::json json = nlohmann::json::parse(summary.to_json(sim));
  add_outcome(json, outcome, false);
  std::ofstream(dir / "summary.json") << json.dump(2) << "\n";  // the last file written
  std::printf("%s%s", summary.to_text(sim).c_str(), outcome_line(outcome).c_str());
  std::printf(
      "results: %s (frames frame_*.obj%s, steps.jsonl, summary.json)\n", dir.c_str(),
      sim.scene().obstacles.empty() ? "" : " with the obstacles beside them in obstacles_*.obj");
  return finish(outcome);
}

/// A solve's log line, tagged with its level and kind ("step" or "settle").
std::string tagged_line(const StepRecord& record, int level, const char* kind) {
  nlohmann::json line = nlohmann::json::parse(to_json_line(record));
  line["level"] = level;
  line["kind"] = kind;
  return line.dump();
}

/// One row per level: its size, work, time and outcome (and error once the finest converged).
/// Levels not reached (a failed run) have no row.
nlohmann::json level_rows(const ProgressiveSimulation& psq, const std::vector<int>& crossings) {
  nlohmann::json rows = nlohmann::json::array();
  for (int l = 0; l < static_cast<int>(crossings.size()); ++l) {
    const LevelRecord& r = psq.records()[l];
    nlohmann::json row = {{"level", l},
                          {"vertices", psq.hierarchy().levels[l].rest.num_vertices()},
                          {"steps", r.steps},
                          {"settles", r.settles},
                          {"newton_iterations", r.newton_iterations},
                          {"solve_seconds", r.solve_seconds},
                          {"refine_seconds", r.refine_seconds},
                          {"equilibrium", r.equilibrium},
                          {"crossing_face_pairs", crossings[l]}};
    const StrainCorrectionStats& c = r.strain_correction;
    if (c.stretch_before > 0.0)  // the refined start met its strain limits (PSQ §4.4.5)
      row["strain_correction"] = {{"strained_faces", c.strained_faces},
                                  {"over_limit_faces", c.over_limit_faces},
                                  {"stretch_before", c.stretch_before},
                                  {"stretch_after", c.stretch_after},
                                  {"newton_iterations", c.newton_iterations},
                                  {"moved_coarse_vertices", c.moved_coarse_vertices}};
    if (const auto error = psq.error_against_finest(l)) {
      row["error_rms"] = error->rms;
      row["error_max"] = error->max;
    }
    if (!r.reactions.empty()) row["reactions"] = reactions_json(r.reactions);
    rows.push_back(row);
  }
  return rows;
}

std::string level_table(const nlohmann::json& rows) {
  const double nan = std::numeric_limits<double>::quiet_NaN();  // no error measured
  std::string text =
      "level  vertices  steps  settles  Newton  solve s  refine s  equilibrium  error RMS  "
      "error max\n";
  for (const auto& r : rows) {
    char line[200];
    std::snprintf(line, sizeof line, "%5d  %8d  %5d  %7d  %6d  %7.3g  %8.3g  %11s  %9.3g  %9.3g\n",
                  r["level"].get<int>(), r["vertices"].get<int>(), r["steps"].get<int>(),
                  r["settles"].get<int>(), r["newton_iterations"].get<int>(),
                  r["solve_seconds"].get<double>(), r["refine_seconds"].get<double>(),
                  r["equilibrium"].get<bool>() ? "yes" : "no", r.value("error_rms", nan),
                  r.value("error_max", nan));
    text += line;
  }
  return text;
}

/// PSQ (Zhang et al. 2023, Algorithm 1): the load script previewed on level 0, its
/// equilibrium, then each finer level refined (§4.4) and settled to equilibrium.
int run_progressive(Scene scene, const RunCommand& opt) {
  Timer total;
  ProgressiveSimulation psq(std::move(scene));
  const Scene& s = psq.scene();
  const int steps = opt.steps > 0 ? opt.steps : s.num_steps();
  const int finest = psq.finest();
  const fs::path dir(opt.out_dir);
  std::ofstream log = open_log(dir);
  // A preview frame is the coarsest level's own state on its own mesh, which contact keeps
  // intersection-free, beside the obstacles as that level meets them (progressive ones as
  // coarse copies). The prolonged preview on the finest mesh is what the proxy energy
  // measures, but can cross itself and enter obstacles (the twist: up to 177 crossing face
  // pairs): written apart, as prolonged_*.obj.
  const TriangleMesh& fine = psq.hierarchy().levels.back().rest;
  const TriangleMesh& coarse = psq.hierarchy().levels[0].rest;
  const auto write_frame = [&](int frame) {
    write_mesh(numbered(dir, "frame_", frame), TriangleMesh{psq.positions(0), coarse.faces});
    write_nonempty(numbered(dir, "obstacles_", frame), met_obstacles(psq.current()));
    if (finest > 0)
      write_mesh(numbered(dir, "prolonged_", frame),
                 TriangleMesh{psq.positions(finest), fine.faces});
  };
  ProgressBar bar(s.name + " (preview, then levels)", steps + finest + 1);
  Outcome outcome;
  std::vector<int> crossings;
  std::string where = "the start";  // what was under way, for a failure's message
  try {
    write_frame(0);
    for (int k = 1; k <= steps; ++k) {
      where = "load step " + std::to_string(k) + " (preview on level 0)";
      stop_if_interrupted();
      const StepRecord record = psq.step();
      log << tagged_line(record, 0, "step") << "\n";
      if (const auto why = solve_failure(record, psq.current().positions()))
        fail(Status::numerical_failure, *why);
      outcome.last_good_step = k;
      if (k % s.output_every == 0 || k == steps) write_frame(k);
      if (!opt.quiet) bar.update(k);
    }
    for (int level = 0;; ++level) {
      where = "settling level " + std::to_string(level);
      for (int k = 0; k < opt.max_settles && !psq.records()[level].equilibrium; ++k) {
        stop_if_interrupted();
        const StepRecord record = psq.settle();
        log << tagged_line(record, level, "settle") << "\n";
        if (const auto why = solve_failure(record, psq.current().positions()))
          fail(Status::numerical_failure, *why);
      }
      const TriangleMesh& own = psq.hierarchy().levels[level].rest;
      const std::string name = "level_" + std::to_string(level);
      write_mesh((dir / (name + ".obj")).string(), TriangleMesh{psq.positions(level), own.faces});
      write_nonempty((dir / (name + "_obstacles.obj")).string(), met_obstacles(psq.current()));
      crossings.push_back(static_cast<int>(psq.current().intersecting_face_pairs()));
      if (psq.records()[level].equilibrium) outcome.last_good_level = level;
      if (!opt.quiet) bar.update(steps + level + 1);
      if (level == finest || opt.preview_only) break;
      where = "refining level " + std::to_string(level) + " into " + std::to_string(level + 1);
      stop_if_interrupted();
      psq.refine();
    }
    const int last_level = opt.preview_only ? 0 : finest;  // the level the run ends on
    const LevelRecord& last = psq.records()[last_level];
    if (!last.equilibrium) {
      outcome.status = "not_converged";
      char why[256];
      std::snprintf(why, sizeof why,
                    "the %s level %d did not reach equilibrium in %d settles (gradient norm "
                    "%.3g; --max-settles raises the limit)",
                    opt.preview_only ? "previewed" : "finest", last_level, last.settles,
                    last.gradient_norm);
      outcome.message = why;
    } else if (opt.preview_only) {
      outcome.message = "preview only (--preview-only): level 0 of " + std::to_string(finest + 1) +
                        " solved, the finer levels not";
    }
  } catch (const Error& e) {
    outcome.fail(where, e);
  }
  if (!opt.quiet) bar.finish();
  const nlohmann::json rows = level_rows(psq, crossings);
  nlohmann::json summary = {{"scene", s.name},
                            {"method", "progressive shell quasistatics"},
                            {"load_steps", steps},
                            {"wall_seconds", total.seconds()},
                            {"levels", rows}};
  add_outcome(summary, outcome, true);
  if (opt.preview_only) summary["preview_only"] = true;
  if (s.contact.crossing_start)  // the scene opted into a crossing rest shape (issue 28)
    summary["input_crossing_face_pairs"] = psq.input_crossing_pairs();
  log.close();  // flushed before the summary, which is written last
  std::ofstream(dir / "summary.json") << summary.dump(2) << "\n";  // the last file written
  std::printf(
      "%s: progressive, %d load steps previewed on level 0, %d levels, %.3g s (errors: "
      "distance to the converged finest result over its bounding-box diagonal)\n%s%s",
      s.name.c_str(), steps, finest + 1, total.seconds(), level_table(rows).c_str(),
      outcome_line(outcome).c_str());
  if (s.contact.crossing_start)
    std::printf("the input crosses itself in %d face pairs (contact.crossing_start)\n",
                psq.input_crossing_pairs());
  std::printf(
      "results: %s (frame_*.obj: the preview, level 0's own mesh%s; prolonged_*.obj: the "
      "preview prolonged to the finest mesh, may cross; level_*.obj%s; steps.jsonl; "
      "summary.json)\n",
      dir.c_str(), s.obstacles.empty() ? "" : ", obstacles_*.obj: the obstacles it met",
      s.obstacles.empty() ? "" : " and level_*_obstacles.obj");
  return finish(outcome);
}

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunCommand& options) {
  CLI::App* cmd = app.add_subcommand(
      "run",
      "simulate a scene and write meshes and logs (progressively when it has a 'progressive' "
      "section: PSQ for quasistatic scenes, Progressive Dynamics for dynamic ones)");
  cmd->add_option("scene", options.scene_path, "scene file (JSON)")->required();
  cmd->add_option("--out", options.out_dir, "output folder (created)")->required();
  cmd->add_option("--steps", options.steps, "override the number of load steps")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-settles", options.max_settles,
                  "progressive: solves per level while waiting for equilibrium")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--direct", options.direct,
                "solve a progressive scene directly on its finest mesh instead");
  cmd->add_flag("--preview-only", options.preview_only,
                "progressive: stop after the preview on level 0 (its load steps and settling, or "
                "its animation); no refinement");
  cmd->add_flag("--quiet", options.quiet, "no progress bar");
  cmd->footer(
      "Exit status: 0 the run ended \"ok\"; 2 bad input (a malformed scene or mesh, a "
      "quasistatic body that nothing holds), nothing written; 3 the simulation failed (a "
      "non-finite solve, an error after the start) or did not converge (the finest level, or a "
      "direct run's last step). summary.json, written last, records \"status\" and "
      "\"message\".");
  return cmd;
}

int run_run_command(const RunCommand& options) {
  Scene scene = load_scene_file(options.scene_path);
  validate_scene(scene);
  const bool progressive = scene.progressive.enabled() && !options.direct;
  if (options.preview_only && !progressive)
    fail(Status::invalid_argument, "--preview-only needs a progressive run: " + scene.name +
                                       " has no coarse levels, or --direct was given");
  catch_interrupt();  // Ctrl-C: a "cancelled" summary, not a torn folder
  if (progressive && scene.mode == StepMode::dynamic)
    return run_progressive_dynamics(std::move(scene), options);
  if (progressive) return run_progressive(std::move(scene), options);
  return run_direct(std::move(scene), options);
}

}  // namespace progsim::cli
