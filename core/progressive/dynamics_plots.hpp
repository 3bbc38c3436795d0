#pragma once
/// @file Plots of animations level by level (PD Figs. 9 and 19): kinetic energy and
/// centre-of-mass height over time, centre-of-mass deviation over time, wall time per level.
#include <string>
#include <vector>

#include "common/types.hpp"
#include "progressive/progressive_dynamics.hpp"

namespace progsim {

/// One level's trajectory to plot.
struct LevelCurve {
  std::string method;  ///< "progressive" or "direct": one series per method in the time plot
  int level = 0;
  const DynamicLevelRecord* record = nullptr;  ///< borrowed for the call
};

/// Writes kinetic_energy.png, center_of_mass_height.png (the centre of mass along `up`),
/// com_deviation.png (each curve's deviation from its method's reference) and time_by_level.png
/// (wall time against vertices, one series per method) into `dir`, titled with `scene`, one
/// series per curve. Returns the file names. Throws Error(io_error) as write_line_plot_png.
std::vector<std::string> write_dynamics_plots(const std::string& scene,
                                              const std::vector<LevelCurve>& curves, const Vec3& up,
                                              const std::string& dir);

/// The unit vector against gravity (+y without gravity): what "height" means in the plots.
Vec3 up_direction(const Vec3& gravity);

}  // namespace progsim
