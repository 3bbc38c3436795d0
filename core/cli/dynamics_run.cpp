#include "cli/dynamics_run.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/progress_bar.hpp"
#include "cli/run_outcome.hpp"
#include "cli/run_output.hpp"
#include "common/error.hpp"
#include "common/timer.hpp"
#include "mesh/mesh_io.hpp"
#include "progressive/dynamics_plots.hpp"
#include "progressive/dynamics_report.hpp"
#include "progressive/progressive_animation.hpp"
#include "sim/obstacle_script.hpp"

namespace fs = std::filesystem;

namespace progsim::cli {
namespace {

/// The scene's obstacles stacked into one mesh, posed by `script` at time t.
TriangleMesh scripted_obstacles(const Scene& scene, const ObstacleScript& script, double t) {
  Faces faces(0, 3);
  int vertices = 0;
  for (const Obstacle& o : scene.obstacles) {
    faces.conservativeResize(faces.rows() + o.mesh.num_faces(), 3);
    faces.bottomRows(o.mesh.num_faces()) = o.mesh.faces.array() + vertices;
    vertices += o.mesh.num_vertices();
  }
  return {script.at(t), faces};
}

/// Writes the frames of an animation as they are computed.
class FrameWriter {
 public:
  FrameWriter(const ProgressiveAnimation& pd, int steps, fs::path dir)
      : pd_(pd), script_(pd.scene()), steps_(steps), dir_(std::move(dir)) {}

  /// Writes frames first..last of `level` that fall on the output grid (every output_every
  /// steps, and the last step); on level 0 the obstacles beside them.
  void write(int level, int first, int last) const {
    const fs::path folder = dir_ / ("level_" + std::to_string(level));
    fs::create_directories(folder);
    const Faces& faces = pd_.surface_faces(level);
    Positions x, v;
    for (int frame = first; frame <= last; ++frame) {
      if (frame % pd_.scene().output_every != 0 && frame != steps_) continue;
      pd_.read_frame(level, frame, x, v);
      write_mesh(numbered(folder, "frame_", frame), TriangleMesh{x, faces});
      if (level == 0 && !pd_.scene().obstacles.empty())
        write_mesh(numbered(dir_, "obstacles_", frame),
                   scripted_obstacles(pd_.scene(), script_, frame * pd_.scene().time_step));
    }
  }

 private:
  const ProgressiveAnimation& pd_;
  ObstacleScript script_;
  int steps_;
  fs::path dir_;
};

/// Throws Error(numerical_failure) naming the first step of `level` whose state is not finite.
void check_finite(const DynamicLevelRecord& record, int level) {
  for (const DynamicStepRecord& s : record.steps)
    if (!std::isfinite(s.motion.kinetic_energy) || !s.motion.center_of_mass.allFinite())
      fail(Status::numerical_failure, "level " + std::to_string(level) + ", step " +
                                          std::to_string(s.step) + ": its state is not finite");
}

/// The preview: `steps` steps on level 0, each logged and its frame written.
void preview(ProgressiveAnimation& pd, int steps, const FrameWriter& frames, std::ofstream& log,
             Outcome& outcome, bool quiet) {
  ProgressBar bar(pd.scene().name + " (preview, level 0)", steps);
  frames.write(0, 0, 0);
  for (int k = 1; k <= steps; ++k) {
    stop_if_interrupted();
    const StepRecord step = pd.step_preview();
    log << dynamic_step_json(0, pd.record(0).steps.back()).dump() << "\n";
    if (const auto why = solve_failure(step, pd.preview().positions()))
      fail(Status::numerical_failure, "step " + std::to_string(k) + ": " + *why);
    outcome.last_good_step = k;
    frames.write(0, k, k);
    if (!quiet) bar.update(k);
  }
  if (!quiet) bar.finish();
}

/// Animates the next level over the previewed steps, then logs it and writes its frames.
void refine(ProgressiveAnimation& pd, const FrameWriter& frames, std::ofstream& log, bool quiet) {
  const int level = pd.level() + 1;
  const int steps = pd.num_frames(0) - 1;
  ProgressBar bar(pd.scene().name + " (level " + std::to_string(level) + ")", steps);
  pd.refine([&](int done, int) {
    if (!quiet) bar.update(done);
    return !interrupted();
  });
  if (!quiet) bar.finish();
  for (const DynamicStepRecord& s : pd.record(level).steps)
    log << dynamic_step_json(level, s).dump() << "\n";
  check_finite(pd.record(level), level);
  frames.write(level, 0, steps);
}

/// "not_converged" when the level the run ends on has steps short of the Newton tolerance.
void check_converged(const DynamicLevelSummary& last, Outcome& outcome) {
  if (last.all_converged()) return;
  outcome.status = "not_converged";
  outcome.message = "level " + std::to_string(last.level) + ": " +
                    std::to_string(last.steps - last.converged_steps) + " of " +
                    std::to_string(last.steps) +
                    " steps ended short of the Newton tolerance (solver.max_newton_iterations)";
}

}  // namespace

int run_progressive_dynamics(Scene scene, const RunCommand& opt) {
  Timer total;
  const std::unique_ptr<ProgressiveAnimation> animation =
      make_progressive_animation(std::move(scene));
  ProgressiveAnimation& pd = *animation;
  const Scene& s = pd.scene();
  const int steps = opt.steps > 0 ? opt.steps : s.num_steps();
  const fs::path dir(opt.out_dir);
  std::ofstream log = open_log(dir);
  const FrameWriter frames(pd, steps, dir);
  Outcome outcome;
  std::string where = "the preview (level 0)";  // what was under way, for a failure's message
  try {
    preview(pd, steps, frames, log, outcome, opt.quiet);
    while (!opt.preview_only && pd.level() < pd.finest()) {
      where = "animating level " + std::to_string(pd.level() + 1);
      stop_if_interrupted();
      refine(pd, frames, log, opt.quiet);
    }
  } catch (const Error& e) {
    outcome.fail(where, e);
  }
  std::vector<DynamicLevelSummary> rows;
  std::vector<LevelCurve> curves;
  nlohmann::json levels = nlohmann::json::array();
  for (int l = 0; l <= pd.level() && pd.num_frames(l) > 1; ++l) {
    rows.push_back(summarize_level(l, pd.record(l)));
    curves.push_back({"progressive", l, &pd.record(l)});
    levels.push_back(to_json(rows.back()));
    if (rows.back().finite && rows.back().all_converged()) outcome.last_good_level = l;
  }
  if (outcome.ok() && !rows.empty()) check_converged(rows.back(), outcome);
  if (outcome.ok() && opt.preview_only)
    outcome.message = "preview only (--preview-only): level 0 of " +
                      std::to_string(pd.finest() + 1) + " animated, the finer levels not";
  log.close();
  nlohmann::json summary = {{"scene", s.name},
                            {"method", pd.method()},
                            {"steps", steps},
                            {"time_step", s.time_step},
                            {"prediction", prediction_name(s.progressive.prediction)},
                            {"consistency_weight", s.progressive.consistency_weight},
                            {"wall_seconds", total.seconds()},
                            {"levels", levels}};
  try {
    if (!curves.empty())
      summary["plots"] = write_dynamics_plots(s.name, curves, up_direction(s.gravity), dir);
  } catch (const Error& e) {
    outcome.fail("writing the plots", e);
  }
  add_outcome(summary, outcome, true);
  if (opt.preview_only) summary["preview_only"] = true;
  std::ofstream(dir / "summary.json") << summary.dump(2) << "\n";  // the last file written
  std::printf(
      "%s: %s, %d steps of %.3g s previewed on level 0, %d levels, %.3g s "
      "(CoM dev.: how far the level's centre of mass moved away from the preview's since frame 0)\n"
      "%s%s",
      s.name.c_str(), pd.method(), steps, s.time_step, pd.finest() + 1, total.seconds(),
      dynamic_level_table(rows).c_str(), outcome_line(outcome).c_str());
  std::printf(
      "results: %s (level_*/frame_*.obj: each level's frames on its own mesh%s; steps.jsonl; "
      "kinetic_energy.png, center_of_mass_height.png, com_deviation.png, time_by_level.png; "
      "summary.json)\n",
      dir.c_str(), s.obstacles.empty() ? "" : "; obstacles_*.obj: the obstacles' scripted pose");
  return finish(outcome);
}

}  // namespace progsim::cli
