// progsim command-line interface: run scenes, build hierarchies, print build information and
// parameters.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "cli/accuracy_command.hpp"
#include "cli/hierarchy_command.hpp"
#include "cli/progress_bar.hpp"
#include "common/build_info.hpp"
#include "common/error.hpp"
#include "mesh/mesh_io.hpp"
#include "scene/parameter_table.hpp"
#include "scene/scene_json.hpp"
#include "sim/direct_simulation.hpp"
#include "sim/run_summary.hpp"

namespace fs = std::filesystem;
using namespace progsim;

namespace {

struct RunOptions {
  std::string scene_path;
  std::string out_dir;
  int steps = 0;  // 0: from the scene
  bool quiet = false;
};

std::string frame_path(const fs::path& dir, int frame) {
  std::ostringstream name;
  name << "frame_" << std::setw(5) << std::setfill('0') << frame << ".obj";
  return (dir / name.str()).string();
}

void write_frame(const fs::path& dir, int frame, const DirectSimulation& sim) {
  write_mesh(frame_path(dir, frame), TriangleMesh{sim.positions(), sim.model().rest.faces});
}

int run(const RunOptions& opt) {
  // Everything is loaded and validated before the output folder is touched, so bad input
  // leaves nothing half-written.
  DirectSimulation sim(load_scene_file(opt.scene_path));
  if (sim.scene().progressive.enabled())
    std::fprintf(stderr,
                 "progsim run: solving %s directly on its finest mesh; its progressive levels are "
                 "used by `progsim accuracy`\n",
                 sim.scene().name.c_str());
  const int steps = opt.steps > 0 ? opt.steps : sim.scene().num_steps();
  const fs::path dir(opt.out_dir);
  fs::create_directories(dir);
  std::ofstream log(dir / "steps.jsonl");
  if (!log) fail(Status::io_error, "cannot write " + (dir / "steps.jsonl").string());
  write_frame(dir, 0, sim);
  RunSummary summary;
  cli::ProgressBar bar(sim.scene().name, steps);
  for (int s = 1; s <= steps; ++s) {
    const StepRecord record = sim.step();
    log << to_json_line(record) << "\n";
    summary.add(record);
    if (s % sim.scene().output_every == 0 || s == steps) write_frame(dir, s, sim);
    if (!opt.quiet) bar.update(s);
  }
  if (!opt.quiet) bar.finish();
  std::ofstream(dir / "summary.json") << summary.to_json(sim) << "\n";
  std::printf("%s", summary.to_text(sim).c_str());
  std::printf("results: %s (frames frame_*.obj, steps.jsonl, summary.json)\n", dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"progsim: progressive simulation of cloth, shells and solids"};
  app.require_subcommand(1);
  RunOptions run_options;
  CLI::App* run_cmd = app.add_subcommand("run", "simulate a scene and write meshes and logs");
  run_cmd->add_option("scene", run_options.scene_path, "scene file (JSON)")->required();
  run_cmd->add_option("--out", run_options.out_dir, "output folder (created)")->required();
  run_cmd->add_option("--steps", run_options.steps, "override the number of steps")
      ->check(CLI::PositiveNumber);
  run_cmd->add_flag("--quiet", run_options.quiet, "no progress bar");
  cli::HierarchyCommand hierarchy_options;
  CLI::App* hierarchy_cmd = cli::add_hierarchy_command(app, hierarchy_options);
  cli::AccuracyCommand accuracy_options;
  CLI::App* accuracy_cmd = cli::add_accuracy_command(app, accuracy_options);
  app.add_subcommand("info", "print version and build options")->callback([] {
    std::printf("%s", build_info().c_str());
  });
  app.add_subcommand("params", "print the scene parameter table (Markdown)")->callback([] {
    std::printf("%s", parameter_table_markdown().c_str());
  });
  CLI11_PARSE(app, argc, argv);
  try {
    if (run_cmd->parsed()) return run(run_options);
    if (hierarchy_cmd->parsed()) return cli::run_hierarchy_command(hierarchy_options);
    if (accuracy_cmd->parsed()) return cli::run_accuracy_command(accuracy_options);
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "progsim: error (%s): %s\n", status_name(e.status()), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "progsim: error: %s\n", e.what());
    return 2;
  }
}
