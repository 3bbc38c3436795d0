#include "progressive/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "common/error.hpp"
#include "common/timer.hpp"
#include "progressive/progressive_simulation.hpp"
#include "progressive/state_distance.hpp"
#include "report/line_plot.hpp"

namespace progsim {
namespace {

using Method = AccuracyRow::Method;

/// Reports progress; throws Error(cancelled) when the callback says stop.
void notify(AccuracyProgress progress, void* user, double fraction, const std::string& phase) {
  if (progress && !progress(user, fraction, phase.c_str()))
    fail(Status::cancelled, "accuracy run cancelled during " + phase);
}

/// One phase of the run ("progressive level 0", "direct level 2", …), spanning [start, start +
/// width) of the whole run's progress.
struct Phase {
  AccuracyProgress progress;
  void* user;
  std::string name;
  double start, width;
  /// Reports the phase begun; throws Error(cancelled) when the callback says stop.
  void begin() const { notify(progress, user, start, name); }
  /// Reports `done` of the load script's `total` steps solved, so that a direct solve that takes
  /// hours is not silent; throws Error(cancelled) when the callback says stop.
  void load_step(int done, int total) const {
    notify(progress, user, start + width * done / total,
           name + ", load step " + std::to_string(done) + " of " + std::to_string(total));
  }
};

/// The row's errors: x against the reference (PSQ accuracy, DESIGN.md metrics).
void set_errors(AccuracyRow& row, const Positions& x, const Positions& reference, double diagonal) {
  const StateDistance d = state_distance(x, reference, diagonal);
  row.error_rms = d.rms;
  row.error_max = d.max;
}

/// The scene solved directly on `level` over its load script and settled to equilibrium (at
/// most `max_settles` more solves, as the progressive levels), prolonged to the finest mesh.
/// Stops unfinished within the Newton iteration that takes it past `time_limit` seconds (0: no
/// limit); a load step stopped inside is not counted as solved.
AccuracyRow direct_row(const Scene& scene, const ProgressiveSimulation& psq, int level,
                       int max_settles, double time_limit, const Phase& phase,
                       Positions& prolonged) {
  AccuracyRow row;
  row.method = Method::direct;
  row.level = level;
  Timer timer;
  LevelSimulation sim(scene, SimulationLevel{psq.shared_hierarchy(), level, {}});
  if (time_limit > 0.0) sim.set_interrupt([&] { return timer.seconds() > time_limit; });
  StepRecord last;
  const auto stopped = [&] { return last.newton.stop == NewtonStop::interrupted; };
  while (row.load_steps < scene.num_steps()) {
    last = sim.step();
    row.newton_iterations += last.newton.iterations;
    if (stopped()) break;
    phase.load_step(++row.load_steps, scene.num_steps());
  }
  for (int k = 0; k < max_settles && !last.equilibrium && !stopped(); ++k) {
    last = sim.settle();
    row.newton_iterations += last.newton.iterations;
  }
  row.seconds = timer.seconds();
  row.finished = !stopped();
  row.converged = row.finished && last.equilibrium;
  row.intersecting_pairs = static_cast<int>(sim.intersecting_face_pairs());
  row.vertices = sim.model().rest.num_vertices();
  prolonged = level < psq.finest() ? psq.prolong_to_finest(level, Positions(sim.positions()))
                                   : Positions(sim.positions());
  return row;
}

const char* method_name(Method m) {
  return m == Method::progressive ? "progressive" : "direct";
}

/// The row of `method` on `level`, or nullptr.
const AccuracyRow* find_row(const AccuracyReport& report, Method method, int level) {
  for (const AccuracyRow& row : report.rows)
    if (row.method == method && row.level == level) return &row;
  return nullptr;
}

int finest_level(const AccuracyReport& report) {
  int finest = 0;
  for (const AccuracyRow& row : report.rows) finest = std::max(finest, row.level);
  return finest;
}

using RowValue = double (*)(const AccuracyRow&);

/// The rows of `method` as points (x(row), y(row)).
PlotSeries series(const AccuracyReport& report, Method method, std::string label, RowValue x,
                  RowValue y, bool lines) {
  PlotSeries s;
  s.label = std::move(label);
  s.lines = lines;
  for (const AccuracyRow& row : report.rows)
    if (row.method == method) {
      s.x.push_back(x(row));
      s.y.push_back(y(row));
    }
  return s;
}

PlotSpec log_log_plot(const std::string& title, const char* x_label, const char* y_label) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = x_label;
  spec.y_label = y_label;
  spec.log_x = spec.log_y = true;
  return spec;
}

double vertices_of(const AccuracyRow& r) {
  return r.vertices;
}
double seconds_of(const AccuracyRow& r) {
  return r.seconds;
}
double error_max_of(const AccuracyRow& r) {
  return r.error_max;
}
double error_rms_of(const AccuracyRow& r) {
  return r.error_rms;
}

/// Error (max and RMS) against x = time or vertices, one series per method and measure.
void plot(const AccuracyReport& report, bool by_vertices, const std::string& path) {
  PlotSpec spec =
      log_log_plot(report.scene + (by_vertices ? ": error by level" : ": error vs time"),
                   by_vertices ? "vertices of the level" : "wall time (s)",
                   "distance to converged finest / bbox diagonal");
  for (Method m : {Method::progressive, Method::direct})
    for (bool max : {true, false})
      spec.series.push_back(series(report, m,
                                   std::string(method_name(m)) + (max ? ", max" : ", RMS"),
                                   by_vertices ? vertices_of : seconds_of,
                                   max ? error_max_of : error_rms_of, m == Method::progressive));
  write_line_plot_png(spec, path);
}

/// Wall time by level (the converged finest included, whose error a log axis cannot show):
/// progressive until the level's equilibrium, direct for the level alone.
void plot_time(const AccuracyReport& report, const std::string& path) {
  PlotSpec spec =
      log_log_plot(report.scene + ": time by level", "vertices of the level", "wall time (s)");
  spec.series.push_back(series(report, Method::progressive, "progressive, to reach the level",
                               vertices_of, seconds_of, true));
  spec.series.push_back(series(report, Method::direct, "direct, solving the level alone",
                               vertices_of, seconds_of, true));
  write_line_plot_png(spec, path);
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) fail(Status::io_error, "cannot write " + path.string());
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

/// The levels to solve directly: those asked for, each checked, or every level.
std::vector<int> direct_levels(const DirectSolves& direct, int finest) {
  if (!(direct.time_ratio >= 0.0))
    fail(Status::invalid_argument, "direct time ratio must be >= 0 (0: no limit)");
  for (int level : direct.levels)
    if (level < 0 || level > finest)
      fail(Status::invalid_argument, "direct level " + std::to_string(level) +
                                         " does not exist (levels 0.." + std::to_string(finest) +
                                         ")");
  if (!direct.levels.empty()) return direct.levels;
  std::vector<int> all(finest + 1);
  for (int level = 0; level <= finest; ++level) all[level] = level;
  return all;
}

/// A sentence on which obstacle meshes the two methods met, when they differ.
std::string obstacle_resolution(const AccuracyReport& report) {
  const std::vector<int>& counts = report.progressive_obstacle_vertices;
  if (std::all_of(counts.begin(), counts.end(),
                  [&](int n) { return n == report.obstacle_vertices; }))
    return "";
  std::string levels;
  for (int n : counts) levels += (levels.empty() ? "" : ", ") + std::to_string(n);
  return "Obstacles: the progressive levels met " + levels +
         " obstacle vertices (progressive collision objects, PSQ §4.6); every direct solve met "
         "all " +
         std::to_string(report.obstacle_vertices) + ".\n\n";
}

}  // namespace

AccuracyReport run_accuracy(const Scene& scene, int max_settles, AccuracyProgress progress,
                            void* user, const DirectSolves& direct) {
  check_progressive_scene(scene);  // before any work: a crossing input is refused at once
  if (!scene.progressive.enabled())
    fail(Status::invalid_scene, scene.name +
                                    ": an accuracy run needs coarse levels (the scene's "
                                    "'progressive' section)");
  AccuracyReport report;
  report.scene = scene.name;
  notify(progress, user, 0.0, "hierarchy");
  Timer build;
  auto hierarchy = std::make_shared<const MeshHierarchy>(build_scene_hierarchy(scene));
  report.hierarchy_seconds = build.seconds();
  ProgressiveSimulation psq(scene, hierarchy);
  const int finest = psq.finest();
  const std::vector<int> direct_order = direct_levels(direct, finest);
  const double units = finest + 1.0 + direct_order.size();
  std::vector<Positions> prolonged;
  Timer total;
  double excluded = 0.0;  // time the method does not need (checks, prolongation for errors)
  for (int level = 0;; ++level) {
    const Phase phase{progress, user, "progressive level " + std::to_string(level), level / units,
                      1.0 / units};
    phase.begin();
    if (level == 0)
      for (int s = 0; s < scene.num_steps(); ++s) {
        psq.step();
        phase.load_step(s + 1, scene.num_steps());
      }
    else
      psq.refine();
    psq.settle_to_equilibrium(max_settles);
    AccuracyRow row;
    row.level = level;
    row.seconds = total.seconds() - excluded;
    row.vertices = hierarchy->levels[level].rest.num_vertices();
    row.refine_seconds = psq.records()[level].refine_seconds;
    row.newton_iterations = psq.records()[level].newton_iterations;
    row.converged = psq.records()[level].equilibrium;
    row.load_steps = scene.num_steps();
    report.progressive_obstacle_vertices.push_back(psq.records()[level].obstacle_vertices);
    Timer prolong;  // checking and prolonging the state is not the method's work
    row.intersecting_pairs = static_cast<int>(psq.current().intersecting_face_pairs());
    report.rows.push_back(row);
    prolonged.push_back(psq.positions(finest));
    excluded += prolong.seconds();
    if (level == finest) break;
  }
  report.obstacle_vertices = report.progressive_obstacle_vertices.back();  // as direct solves
  const bool of_preview = direct.time_base == DirectSolves::TimeBase::preview;
  report.direct_time_limit =
      direct.time_ratio * (of_preview ? report.rows.front() : report.rows.back()).seconds;
  for (std::size_t k = 0; k < direct_order.size(); ++k) {
    const int level = direct_order[k];
    const Phase phase{progress, user, "direct level " + std::to_string(level),
                      (finest + 1.0 + k) / units, 1.0 / units};
    phase.begin();
    prolonged.emplace_back();
    report.rows.push_back(direct_row(scene, psq, level, max_settles, report.direct_time_limit,
                                     phase, prolonged.back()));
  }
  const Positions reference = prolonged[finest];
  report.diagonal = bounding_box_diagonal(hierarchy->levels.back().rest.vertices);
  for (std::size_t k = 0; k < report.rows.size(); ++k)
    set_errors(report.rows[k], prolonged[k], reference, report.diagonal);
  notify(progress, user, 1.0, "done");
  return report;
}

std::string accuracy_csv(const AccuracyReport& report) {
  std::string csv =
      "method,level,vertices,seconds,refine_seconds,newton_iterations,error_rms,error_max,"
      "intersecting_pairs,converged,load_steps,finished\n";
  for (const AccuracyRow& r : report.rows) {
    char line[256];
    std::snprintf(line, sizeof line, "%s,%d,%d,%.6g,%.6g,%d,%.6g,%.6g,%d,%d,%d,%d\n",
                  method_name(r.method), r.level, r.vertices, r.seconds, r.refine_seconds,
                  r.newton_iterations, r.error_rms, r.error_max, r.intersecting_pairs,
                  r.converged ? 1 : 0, r.load_steps, r.finished ? 1 : 0);
    csv += line;
  }
  return csv;
}

std::string accuracy_markdown(const AccuracyReport& report) {
  std::string md = "# Accuracy vs time: " + report.scene + "\n\n";
  md +=
      "Errors: distance to the converged finest progressive solution over the bounding-box "
      "diagonal (" +
      format("%.4g", report.diagonal) +
      " m), after prolonging each level to "
      "the finest mesh. Hierarchy built in " +
      format("%.3g", report.hierarchy_seconds) +
      " s (not in the times below). Crossing face pairs: CGAL's exact check of the level's "
      "final state, shell and obstacles.\n\n";
  md += obstacle_resolution(report);
  md +=
      "| method | level | vertices | time (s) | refinement (s) | Newton iterations | error RMS "
      "| error max | crossing face pairs | converged | load steps |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const AccuracyRow& r : report.rows)
    md += std::string("| ") + method_name(r.method) + " | " + std::to_string(r.level) + " | " +
          std::to_string(r.vertices) + " | " + format("%.3g", r.seconds) + " | " +
          format("%.3g", r.refine_seconds) + " | " + std::to_string(r.newton_iterations) + " | " +
          format("%.3g", r.error_rms) + " | " + format("%.3g", r.error_max) + " | " +
          std::to_string(r.intersecting_pairs) + " | " + (r.converged ? "yes" : "no") + " | " +
          std::to_string(r.load_steps) + (r.finished ? "" : ", stopped unfinished") + " |\n";
  const int finest = finest_level(report);
  const AccuracyRow* preview = find_row(report, Method::progressive, 0);
  const AccuracyRow* full = find_row(report, Method::progressive, finest);
  const AccuracyRow* direct = find_row(report, Method::direct, finest);
  if (!preview || !full || !direct) return md;
  double refine = 0.0;
  for (const AccuracyRow& r : report.rows)
    if (r.method == Method::progressive) refine += r.refine_seconds;
  // A direct solve stopped unfinished took at least its seconds: the ratios are lower bounds.
  const std::string at_least = direct->finished ? "" : ">= ";
  md += "\nMeasured in this run:\n\n";
  if (!direct->finished)
    md += "- the direct finest solve was stopped unfinished after " +
          format("%.3g", direct->seconds) + " s, at load step " +
          std::to_string(direct->load_steps) + " of " + std::to_string(full->load_steps) +
          ": its ratios below are lower bounds\n";
  md += "- coarse preview vs direct finest solve: " + format("%.3g", preview->seconds) + " s vs " +
        at_least + format("%.3g", direct->seconds) + " s, " + at_least +
        format("%.3g", direct->seconds / preview->seconds) + "x faster\n";
  md += "- progressive to the converged finest vs direct finest solve: " +
        format("%.3g", full->seconds) + " s vs " + at_least + format("%.3g", direct->seconds) +
        " s, " + at_least + format("%.3g", direct->seconds / full->seconds) + "x\n";
  if (const AccuracyRow* coarse = find_row(report, Method::direct, 0))
    md += "- coarse preview vs direct coarse solve, error RMS (max): " +
          format("%.3g", preview->error_rms) + " (" + format("%.3g", preview->error_max) + ") vs " +
          format("%.3g", coarse->error_rms) + " (" + format("%.3g", coarse->error_max) + ")\n";
  md += "- share of the progressive time in refinement: " +
        format("%.1f", 100.0 * refine / full->seconds) + " %\n";
  md += "- direct finest vs converged progressive finest: RMS " +
        format("%.3g", direct->error_rms) + ", max " + format("%.3g", direct->error_max) +
        " (non-zero where the two reach different equilibria)\n";
  return md;
}

void write_accuracy_report(const AccuracyReport& report, const std::string& dir) {
  const std::filesystem::path out(dir);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) fail(Status::io_error, "cannot create " + out.string() + ": " + ec.message());
  write_text(out / "accuracy.csv", accuracy_csv(report));
  write_text(out / "accuracy.md", accuracy_markdown(report));
  plot(report, false, (out / "error_vs_time.png").string());
  plot(report, true, (out / "error_by_level.png").string());
  plot_time(report, (out / "time_by_level.png").string());
}

}  // namespace progsim
