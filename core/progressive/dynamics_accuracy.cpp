#include "progressive/dynamics_accuracy.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "common/error.hpp"
#include "progressive/dynamics_plots.hpp"
#include "progressive/dynamics_report.hpp"

namespace progsim {
namespace {

/// Progress over the whole run: phase `phase` of `phases`, `done` of its `total` steps.
struct RunProgress {
  AccuracyProgress progress;
  void* user;
  int phases;

  bool report(int phase, int done, int total, const std::string& name) const {
    if (!progress) return true;
    const double fraction = (phase + static_cast<double>(done) / total) / phases;
    const std::string what =
        name + ", step " + std::to_string(done) + " of " + std::to_string(total);
    return progress(user, fraction, what.c_str());
  }
  /// As report(); throws Error(cancelled) when the callback says stop.
  void step(int phase, int done, int total, const std::string& name) const {
    if (!report(phase, done, total, name)) fail(Status::cancelled, name + " was cancelled");
  }
};

/// Level `level` of `animation` animated directly over `steps` steps; its centre-of-mass
/// deviation is taken from `coarsest` (the direct coarsest level's record; nullptr for the
/// coarsest itself).
DynamicLevelRecord direct_level(const ProgressiveAnimation& animation, int level, int steps,
                                const DynamicLevelRecord* coarsest, const RunProgress& progress,
                                int phase) {
  const std::unique_ptr<LevelSimulation> sim = animation.direct_level(level);
  DynamicLevelRecord record = start_record(*sim);
  const std::string name = "direct level " + std::to_string(level);
  for (int t = 0; t < steps; ++t) {
    const StepRecord step = sim->step();
    const double deviation = coarsest && step.motion
                                 ? com_deviation(step.motion->center_of_mass, record, *coarsest, t)
                                 : 0.0;
    add_dynamic_step(record, step, deviation, 0.0);
    progress.step(phase, t + 1, steps, name);
  }
  record.terms = sim->term_totals();
  return record;
}

const char* const kMethods[] = {"progressive", "direct"};

/// Both methods' records, progressive first.
std::vector<LevelCurve> curves(const DynamicsAccuracyReport& report) {
  std::vector<LevelCurve> all;
  for (int m = 0; m < 2; ++m) {
    const auto& records = m == 0 ? report.progressive : report.direct;
    for (std::size_t l = 0; l < records.size(); ++l)
      all.push_back({kMethods[m], static_cast<int>(l), &records[l]});
  }
  return all;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) fail(Status::io_error, "cannot write " + path.string());
}

}  // namespace

DynamicsAccuracyReport run_dynamics_accuracy(const Scene& scene, AccuracyProgress progress,
                                             void* user) {
  if (!scene.progressive.enabled() || scene.mode != StepMode::dynamic)
    fail(Status::invalid_scene,
         scene.name + ": a dynamic accuracy run needs a dynamic scene with coarse levels");
  const std::unique_ptr<ProgressiveAnimation> animation = make_progressive_animation(scene);
  ProgressiveAnimation& pd = *animation;
  DynamicsAccuracyReport report;
  report.scene = scene.name;
  report.method = pd.method();
  report.steps = scene.num_steps();
  report.time_step = scene.time_step;
  report.up = up_direction(scene.gravity);
  const int levels = pd.finest() + 1;
  const RunProgress run{progress, user, 2 * levels};
  for (int t = 0; t < report.steps; ++t) {
    pd.step_preview();
    run.step(0, t + 1, report.steps, "progressive level 0");
  }
  for (int level = 1; level < levels; ++level)
    pd.refine([&](int done, int total) {
      return run.report(level, done, total, "progressive level " + std::to_string(level));
    });
  for (int level = 0; level < levels; ++level) report.progressive.push_back(pd.record(level));
  for (int level = 0; level < levels; ++level)
    report.direct.push_back(direct_level(
        pd, level, report.steps, level > 0 ? &report.direct[0] : nullptr, run, levels + level));
  return report;
}

std::string dynamics_accuracy_csv(const DynamicsAccuracyReport& report) {
  std::string csv =
      "method,level,vertices,seconds,newton_iterations,steps,converged_steps,max_com_deviation,"
      "mean_com_deviation,mean_continuity,max_consistency\n";
  for (const LevelCurve& c : curves(report)) {
    const DynamicLevelSummary r = summarize_level(c.level, *c.record);
    char line[320];
    std::snprintf(line, sizeof line, "%s,%d,%d,%.6g,%d,%d,%d,%.6g,%.6g,%.6g,%.6g\n",
                  c.method.c_str(), r.level, r.vertices, r.seconds, r.newton_iterations, r.steps,
                  r.converged_steps, r.max_com_deviation, r.mean_com_deviation, r.mean_continuity,
                  r.max_consistency);
    csv += line;
  }
  return csv;
}

std::string dynamics_trajectory_csv(const DynamicsAccuracyReport& report) {
  std::string csv =
      "method,level,step,time,kinetic_energy,com_x,com_y,com_z,com_deviation,newton_iterations,"
      "converged\n";
  for (const LevelCurve& c : curves(report))
    for (const DynamicStepRecord& s : c.record->steps) {
      const Vec3& com = s.motion.center_of_mass;
      char line[320];
      std::snprintf(line, sizeof line, "%s,%d,%d,%.6g,%.9g,%.9g,%.9g,%.9g,%.6g,%d,%d\n",
                    c.method.c_str(), c.level, s.step, s.time, s.motion.kinetic_energy, com.x(),
                    com.y(), com.z(), s.com_deviation, s.newton_iterations, s.converged ? 1 : 0);
      csv += line;
    }
  return csv;
}

std::string dynamics_accuracy_markdown(const DynamicsAccuracyReport& report) {
  std::string md =
      "# Progressive against direct animation: " + report.scene + " (" + report.method + ")\n\n";
  char head[256];
  std::snprintf(
      head, sizeof head,
      "%d steps of %.3g s. CoM deviation: distance between how far the level's centre of "
      "mass and its method's coarsest level's have moved since the start (PD Fig. 19): progressive "
      "from the preview, direct from the direct coarsest animation.\n\n",
      report.steps, report.time_step);
  md += head;
  md +=
      "| method | level | vertices | time (s) | Newton iterations | converged steps | CoM dev. "
      "max (m) | CoM dev. mean (m) | mean continuity | max consistency (m) |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const LevelCurve& c : curves(report)) {
    const DynamicLevelSummary r = summarize_level(c.level, *c.record);
    char line[320];
    std::snprintf(
        line, sizeof line, "| %s | %d | %d | %.3g | %d | %d of %d | %.3g | %.3g | %.3g | %.3g |\n",
        c.method.c_str(), r.level, r.vertices, r.seconds, r.newton_iterations, r.converged_steps,
        r.steps, r.max_com_deviation, r.mean_com_deviation, r.mean_continuity, r.max_consistency);
    md += line;
  }
  return md;
}

void write_dynamics_accuracy_report(const DynamicsAccuracyReport& report, const std::string& dir) {
  const std::filesystem::path out(dir);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) fail(Status::io_error, "cannot create " + out.string() + ": " + ec.message());
  write_text(out / "accuracy.csv", dynamics_accuracy_csv(report));
  write_text(out / "trajectories.csv", dynamics_trajectory_csv(report));
  write_text(out / "accuracy.md", dynamics_accuracy_markdown(report));
  write_dynamics_plots(report.scene, curves(report), report.up, dir);
}

bool finest_levels_converged(const DynamicsAccuracyReport& report) {
  const auto converged = [](const std::vector<DynamicLevelRecord>& records) {
    return !records.empty() &&
           records.back().converged_steps == static_cast<int>(records.back().steps.size());
  };
  return converged(report.progressive) && converged(report.direct);
}

}  // namespace progsim
