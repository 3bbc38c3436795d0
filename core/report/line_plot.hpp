#pragma once
/// @file Line and scatter plots (linear or logarithmic axes) rendered to PNG files with cairo.
#include <array>
#include <string>
#include <vector>

namespace progsim {

/// One data series: the points (x[i], y[i]) in the given order. A point with a non-finite
/// coordinate, or a coordinate ≤ 0 on a logarithmic axis, is skipped: it is not drawn, does
/// not count for the axis ranges, and breaks the polyline in two.
struct PlotSeries {
  std::string label;         ///< legend text (the series is listed even if nothing is drawn)
  std::vector<double> x, y;  ///< coordinates; both vectors have the same length
  bool lines = true;         ///< a polyline through the points in the given order
  bool markers = true;       ///< a filled circle at every point
};

/// A whole plot: axes, image size in pixels and the series, drawn in order (later on top).
struct PlotSpec {
  std::string title, x_label, y_label;  ///< empty texts are left out (and take no room)
  bool log_x = false, log_y = false;    ///< base-10 logarithmic axes
  int width = 900, height = 600;        ///< image size in pixels, each in [100, 10000]
  std::vector<PlotSeries> series;       ///< at least one
};

/// The data → pixel mapping of a laid-out plot. Pixel coordinates grow rightwards and
/// downwards from the image's top-left corner; the plot area is [left, right] × [top, bottom].
struct PlotFrame {
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;  ///< data values at the plot area's edges
  double left = 0, right = 1, top = 0, bottom = 1;    ///< plot area edges in pixels
  bool log_x = false, log_y = false;                  ///< logarithmic axes

  /// The pixel position (x, y) of the data point (x, y); points outside the axis ranges map
  /// outside the plot area, and a point ≤ 0 on a logarithmic axis maps to NaN.
  std::array<double, 2> to_pixel(double x, double y) const;
};

/// Lays out a plot as write_line_plot_png draws it: the axis ranges contain every drawable
/// point: whole decades 10^floor(log10 min) .. 10^ceil(log10 max) on logarithmic axes (a
/// single power of ten gets a decade either side); on linear ones the data range padded by
/// 3 % each side and rounded outwards to round numbers (a single value is first widened by
/// ±10 %, or ±1 if it is 0). Ticks: decades, or multiples of a 1-2-5 step. The plot area
/// leaves room for the title, axis labels, tick labels and legend. Throws
/// Error(invalid_argument) when there is no series, a series' x and y differ in length (naming
/// it), the width or height is outside [100, 10000], or no point at all is drawable.
PlotFrame layout_plot(const PlotSpec& spec);

/// Renders the plot to a PNG image at `path`: white background, grid, framed plot area with
/// tick labels (decades written "1e-3" on logarithmic axes), axis labels, title and a legend
/// right of the plot area. Throws Error(invalid_argument) as layout_plot does, and
/// Error(io_error) naming the path when the image cannot be rendered or written. The file is
/// written beside `path` and renamed over it, so a failure never leaves a partial file there.
void write_line_plot_png(const PlotSpec& spec, const std::string& path);

/// The colour (r, g, b in [0, 1]) of series k: the colour-blind-safe Okabe-Ito palette of 8
/// colours, blue first, cycling (k mod 8; negative k cycles too).
std::array<double, 3> series_color(int k);

}  // namespace progsim
