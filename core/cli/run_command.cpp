#include "cli/run_command.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/progress_bar.hpp"
#include "common/error.hpp"
#include "common/timer.hpp"
#include "mesh/mesh_io.hpp"
#include "progressive/progressive_simulation.hpp"
#include "scene/scene_json.hpp"
#include "sim/direct_simulation.hpp"
#include "sim/run_summary.hpp"

namespace fs = std::filesystem;

namespace progsim::cli {
namespace {

std::string numbered(const fs::path& dir, const char* stem, int number) {
  std::ostringstream name;
  name << stem << std::setw(5) << std::setfill('0') << number << ".obj";
  return (dir / name.str()).string();
}

std::ofstream open_log(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream log(dir / "steps.jsonl");
  if (!log) fail(Status::io_error, "cannot write " + (dir / "steps.jsonl").string());
  return log;
}

int run_direct(Scene scene, const RunCommand& opt) {
  DirectSimulation sim(std::move(scene));
  const int steps = opt.steps > 0 ? opt.steps : sim.scene().num_steps();
  const fs::path dir(opt.out_dir);
  std::ofstream log = open_log(dir);
  const auto write_frame = [&](int frame) {
    write_mesh(numbered(dir, "frame_", frame),
               TriangleMesh{sim.positions(), sim.model().rest.faces});
  };
  write_frame(0);
  RunSummary summary;
  ProgressBar bar(sim.scene().name, steps);
  for (int s = 1; s <= steps; ++s) {
    const StepRecord record = sim.step();
    log << to_json_line(record) << "\n";
    summary.add(record);
    if (s % sim.scene().output_every == 0 || s == steps) write_frame(s);
    if (!opt.quiet) bar.update(s);
  }
  if (!opt.quiet) bar.finish();
  std::ofstream(dir / "summary.json") << summary.to_json(sim) << "\n";
  std::printf("%s", summary.to_text(sim).c_str());
  std::printf("results: %s (frames frame_*.obj, steps.jsonl, summary.json)\n", dir.c_str());
  return 0;
}

/// A solve's log line, tagged with its level and kind ("step" or "settle").
std::string tagged_line(const StepRecord& record, int level, const char* kind) {
  nlohmann::json line = nlohmann::json::parse(to_json_line(record));
  line["level"] = level;
  line["kind"] = kind;
  return line.dump();
}

/// One row per level: its size, work, time and outcome (and error once the finest converged).
nlohmann::json level_rows(const ProgressiveSimulation& psq, const std::vector<int>& crossings) {
  nlohmann::json rows = nlohmann::json::array();
  for (int l = 0; l <= psq.finest(); ++l) {
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
  const TriangleMesh& fine = psq.hierarchy().levels.back().rest;
  const auto write_frame = [&](int frame) {  // the preview prolonged to the finest mesh
    write_mesh(numbered(dir, "frame_", frame), TriangleMesh{psq.positions(finest), fine.faces});
  };
  write_frame(0);
  ProgressBar bar(s.name + " (preview, then levels)", steps + finest + 1);
  for (int k = 1; k <= steps; ++k) {
    log << tagged_line(psq.step(), 0, "step") << "\n";
    if (k % s.output_every == 0 || k == steps) write_frame(k);
    if (!opt.quiet) bar.update(k);
  }
  std::vector<int> crossings;
  for (int level = 0;; ++level) {
    for (int k = 0; k < opt.max_settles && !psq.records()[level].equilibrium; ++k)
      log << tagged_line(psq.settle(), level, "settle") << "\n";
    const TriangleMesh& own = psq.hierarchy().levels[level].rest;
    write_mesh((dir / ("level_" + std::to_string(level) + ".obj")).string(),
               TriangleMesh{psq.positions(level), own.faces});
    crossings.push_back(static_cast<int>(psq.current().intersecting_face_pairs()));
    if (!opt.quiet) bar.update(steps + level + 1);
    if (level == finest) break;
    psq.refine();
  }
  if (!opt.quiet) bar.finish();
  const nlohmann::json rows = level_rows(psq, crossings);
  const nlohmann::json summary = {{"scene", s.name},
                                  {"method", "progressive shell quasistatics"},
                                  {"load_steps", steps},
                                  {"wall_seconds", total.seconds()},
                                  {"levels", rows}};
  std::ofstream(dir / "summary.json") << summary.dump(2) << "\n";
  std::printf(
      "%s: progressive, %d load steps previewed on level 0, %d levels, %.3g s (errors: "
      "distance to the converged finest result over its bounding-box diagonal)\n%s",
      s.name.c_str(), steps, finest + 1, total.seconds(), level_table(rows).c_str());
  std::printf(
      "results: %s (frame_*.obj: the preview on the finest mesh; level_*.obj; steps.jsonl; "
      "summary.json)\n",
      dir.c_str());
  return 0;
}

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunCommand& options) {
  CLI::App* cmd = app.add_subcommand(
      "run",
      "simulate a scene and write meshes and logs (progressively when it has a 'progressive' "
      "section and is quasistatic)");
  cmd->add_option("scene", options.scene_path, "scene file (JSON)")->required();
  cmd->add_option("--out", options.out_dir, "output folder (created)")->required();
  cmd->add_option("--steps", options.steps, "override the number of load steps")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-settles", options.max_settles,
                  "progressive: solves per level while waiting for equilibrium")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--direct", options.direct,
                "solve a progressive scene directly on its finest mesh instead");
  cmd->add_flag("--quiet", options.quiet, "no progress bar");
  return cmd;
}

int run_run_command(const RunCommand& options) {
  Scene scene = load_scene_file(options.scene_path);
  validate_scene(scene);
  const bool progressive = scene.progressive.enabled() && scene.mode == StepMode::quasistatic;
  if (scene.progressive.enabled() && !progressive && !options.direct)
    std::fprintf(stderr,
                 "progsim run: %s is dynamic; Progressive Dynamics is not implemented, so it is "
                 "solved directly on its finest mesh\n",
                 scene.name.c_str());
  if (progressive && !options.direct) return run_progressive(std::move(scene), options);
  return run_direct(std::move(scene), options);
}

}  // namespace progsim::cli
