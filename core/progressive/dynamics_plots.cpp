#include "progressive/dynamics_plots.hpp"

#include <filesystem>

#include "report/line_plot.hpp"

namespace progsim {
namespace {

using StepValue = double (*)(const DynamicStepRecord&, const Vec3& up);

double kinetic_energy_of(const DynamicStepRecord& s, const Vec3&) {
  return s.motion.kinetic_energy;
}
double height_of(const DynamicStepRecord& s, const Vec3& up) {
  return s.motion.center_of_mass.dot(up);
}
double deviation_of(const DynamicStepRecord& s, const Vec3&) {
  return s.com_deviation;
}

std::string label(const LevelCurve& c) {
  return c.method + " level " + std::to_string(c.level);
}

/// `value` of every step of every curve against time, one series per curve.
void plot_over_time(const std::string& title, const char* y_label,
                    const std::vector<LevelCurve>& curves, StepValue value, const Vec3& up,
                    const std::string& path) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "time (s)";
  spec.y_label = y_label;
  for (const LevelCurve& c : curves) {
    PlotSeries s;
    s.label = label(c);
    s.markers = false;
    for (const DynamicStepRecord& step : c.record->steps) {
      s.x.push_back(step.time);
      s.y.push_back(value(step, up));
    }
    spec.series.push_back(std::move(s));
  }
  write_line_plot_png(spec, path);
}

/// Wall time against the level's vertices, one series per method.
void plot_time(const std::string& title, const std::vector<LevelCurve>& curves,
               const std::string& path) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "vertices of the level";
  spec.y_label = "wall time of the level's steps (s)";
  spec.log_x = spec.log_y = true;
  for (const LevelCurve& c : curves) {
    if (spec.series.empty() || spec.series.back().label != c.method) {
      spec.series.emplace_back();
      spec.series.back().label = c.method;
    }
    spec.series.back().x.push_back(c.record->vertices);
    spec.series.back().y.push_back(c.record->seconds);
  }
  write_line_plot_png(spec, path);
}

}  // namespace

std::vector<std::string> write_dynamics_plots(const std::string& scene,
                                              const std::vector<LevelCurve>& curves, const Vec3& up,
                                              const std::string& dir) {
  const std::filesystem::path out(dir);
  const auto path = [&](const char* name) { return (out / name).string(); };
  plot_over_time(scene + ": kinetic energy", "kinetic energy (J)", curves, kinetic_energy_of, up,
                 path("kinetic_energy.png"));
  plot_over_time(scene + ": centre-of-mass height", "centre of mass along -g (m)", curves,
                 height_of, up, path("center_of_mass_height.png"));
  plot_over_time(scene + ": centre-of-mass deviation from the coarsest level",
                 "|CoM - CoM of level 0| (m)", curves, deviation_of, up, path("com_deviation.png"));
  plot_time(scene + ": time per level", curves, path("time_by_level.png"));
  return {"kinetic_energy.png", "center_of_mass_height.png", "com_deviation.png",
          "time_by_level.png"};
}

Vec3 up_direction(const Vec3& gravity) {
  const double g = gravity.norm();
  return g > 0.0 ? Vec3(-gravity / g) : Vec3(Vec3::UnitY());
}

}  // namespace progsim
