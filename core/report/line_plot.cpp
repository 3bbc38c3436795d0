/// @file Line and scatter plots rendered to PNG with cairo's image surface and toy text API.
#include "report/line_plot.hpp"

#include <cairo.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace progsim {
namespace {

/// Destroys a cairo surface (unique_ptr deleter).
struct SurfaceDeleter {
  void operator()(cairo_surface_t* surface) const { cairo_surface_destroy(surface); }
};
/// Destroys a cairo context (unique_ptr deleter).
struct ContextDeleter {
  void operator()(cairo_t* cr) const { cairo_destroy(cr); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

constexpr int kMinSide = 100;
constexpr int kMaxSide = 10000;
constexpr int kMinExponent = -323;  // 1e-323 is the smallest power of ten above 0 in a double
constexpr int kMaxExponent = 308;
constexpr int kMaxLogLabels = 8;     // at most about this many labelled decades
constexpr int kMaxMinorDecades = 6;  // minor grid lines (2..9 × 10^k) up to this many decades
constexpr int kMaxTicks = 50;        // a safety bound; nice steps give about 5 to 10
constexpr double kLinearPad = 0.03;  // of the data span, so that edge points clear the frame
constexpr double kPad = 12;          // image border
constexpr double kTickLength = 5;
constexpr double kTickGap = 4;     // between a tick and its label
constexpr double kLabelGap = 6;    // between tick labels and the axis label
constexpr double kLegendGap = 14;  // between the plot area and the legend
constexpr double kLegendPad = 8;
constexpr double kSwatch = 24;  // legend line sample length
constexpr double kMarkerRadius = 4;
constexpr double kLineWidth = 2;
constexpr double kBaseWidth = 900;  // image size at which the fonts have their base sizes
constexpr double kBaseHeight = 600;
constexpr const char* kFontFamily = "DejaVu Sans";
using Rgb = std::array<double, 3>;
constexpr Rgb kText = {0.1, 0.1, 0.1};
constexpr Rgb kMajorGrid = {0.85, 0.85, 0.85};
constexpr Rgb kMinorGrid = {0.93, 0.93, 0.93};
constexpr Rgb kLegendBorder = {0.6, 0.6, 0.6};

/// Throws Error(io_error) "<what>: cairo: <reason>" unless `status` is success.
void check_cairo(cairo_status_t status, const std::string& what) {
  if (status != CAIRO_STATUS_SUCCESS)
    fail(Status::io_error, what + ": cairo: " + cairo_status_to_string(status));
}

/// An ARGB32 image surface and a drawing context on it.
struct Canvas {
  SurfacePtr surface;
  ContextPtr cr;
};

/// A width × height canvas; Error(io_error) prefixed by `what` if cairo cannot make it.
Canvas make_canvas(int width, int height, const std::string& what) {
  Canvas canvas;
  canvas.surface.reset(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height));
  check_cairo(cairo_surface_status(canvas.surface.get()), what);
  canvas.cr.reset(cairo_create(canvas.surface.get()));
  check_cairo(cairo_status(canvas.cr.get()), what);
  return canvas;
}

/// Whether the point is drawn: finite, and positive on logarithmic axes.
bool drawable(double x, double y, bool log_x, bool log_y) {
  return std::isfinite(x) && std::isfinite(y) && (!log_x || x > 0) && (!log_y || y > 0);
}

/// "series 'label'" (or "series k" when unlabelled), for error messages.
std::string series_name(const PlotSeries& series, std::size_t k) {
  return series.label.empty() ? "series " + std::to_string(k) : "series '" + series.label + "'";
}

/// Error(invalid_argument) for a spec that cannot be plotted whatever its values.
void validate(const PlotSpec& spec) {
  if (spec.series.empty()) fail(Status::invalid_argument, "line plot: no series to plot");
  const auto outside = [](int side) { return side < kMinSide || side > kMaxSide; };
  if (outside(spec.width) || outside(spec.height))
    fail(Status::invalid_argument, "line plot: image size " + std::to_string(spec.width) + "x" +
                                       std::to_string(spec.height) + " is outside [100, 10000]");
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const PlotSeries& s = spec.series[k];
    if (s.x.size() != s.y.size())
      fail(Status::invalid_argument, "line plot: " + series_name(s, k) + " has " +
                                         std::to_string(s.x.size()) + " x values but " +
                                         std::to_string(s.y.size()) + " y values");
  }
}

/// A closed interval of data values.
struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  bool empty() const { return lo > hi; }
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

/// The x and y ranges of the drawable points of all series (empty if there are none).
std::array<Range, 2> data_ranges(const PlotSpec& spec) {
  std::array<Range, 2> ranges;
  for (const PlotSeries& s : spec.series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (drawable(s.x[i], s.y[i], spec.log_x, spec.log_y)) {
        ranges[0].add(s.x[i]);
        ranges[1].add(s.y[i]);
      }
  return ranges;
}

/// The whole decades [10^a, 10^b], a < b, around the positive data range.
Range log_axis_range(const Range& data) {
  int lo = static_cast<int>(std::floor(std::log10(data.lo)));
  int hi = static_cast<int>(std::ceil(std::log10(data.hi)));
  if (lo == hi) {  // a single power of ten: one decade either side
    --lo;
    ++hi;
  }
  lo = std::clamp(lo, kMinExponent, kMaxExponent - 1);
  hi = std::clamp(hi, lo + 1, kMaxExponent);
  return {std::pow(10.0, lo), std::pow(10.0, hi)};
}

/// A 1, 2 or 5 × 10^k step dividing `span` into about 5 intervals.
double nice_step(double span) {
  const double raw = span / 5;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / magnitude;
  return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * magnitude;
}

/// The data range padded by kLinearPad of its span each side and rounded outwards to
/// multiples of a fifth of a nice step; a single value is first widened by ±10 % (±1 for 0).
Range linear_axis_range(Range data) {
  if (data.lo == data.hi) {
    const double pad = data.lo == 0 ? 1 : 0.1 * std::abs(data.lo);
    data = {data.lo - pad, data.hi + pad};
  }
  const double pad = kLinearPad * (data.hi - data.lo);
  const double unit = nice_step(data.hi - data.lo) / 5;
  return {std::floor((data.lo - pad) / unit) * unit, std::ceil((data.hi + pad) / unit) * unit};
}

/// The axis range for `data`; Error(invalid_argument) if it cannot be represented.
Range axis_range(const Range& data, bool log, const char* axis) {
  const Range range = log ? log_axis_range(data) : linear_axis_range(data);
  if (!std::isfinite(range.lo) || !std::isfinite(range.hi) || !(range.lo < range.hi) ||
      !std::isfinite(range.hi - range.lo))
    fail(Status::invalid_argument, std::string("line plot: cannot lay out the ") + axis +
                                       " axis for data in [" + std::to_string(data.lo) + ", " +
                                       std::to_string(data.hi) + "]");
  return range;
}

/// A grid line; major ticks also get a tick mark and a label.
struct Tick {
  double value;
  std::string label;
  bool major;
};

/// The smallest of 1, 2, 5, 10, 20, 50, ... decades between labels that gives at most
/// kMaxLogLabels intervals over `decades`.
int decades_per_label(int decades) {
  for (int scale = 1;; scale *= 10)
    for (const int every : {scale, 2 * scale, 5 * scale})
      if (decades <= every * kMaxLogLabels) return every;
}

/// Decade ticks "1e-3" at multiples of decades_per_label (other decades get minor grid lines),
/// plus minor grid lines at 2..9 × 10^k when the axis spans few decades.
std::vector<Tick> log_ticks(const Range& range) {
  const int lo = static_cast<int>(std::lround(std::log10(range.lo)));
  const int hi = static_cast<int>(std::lround(std::log10(range.hi)));
  const int every = decades_per_label(hi - lo);
  std::vector<Tick> ticks;
  for (int e = lo; e <= hi; ++e) {
    const double decade = std::pow(10.0, e);
    const bool major = e % every == 0;
    if (major || hi - lo <= kMaxTicks)
      ticks.push_back({decade, major ? "1e" + std::to_string(e) : "", major});
    if (hi - lo <= kMaxMinorDecades && e < hi)
      for (int m = 2; m <= 9; ++m) ticks.push_back({m * decade, "", false});
  }
  return ticks;
}

/// A linear tick label: fixed notation with the step's decimals for moderate magnitudes,
/// exponent notation otherwise.
std::string linear_label(double value, double step, double largest) {
  char text[64];
  if (largest >= 1e-4 && largest < 1e6) {
    const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step))));
    std::snprintf(text, sizeof text, "%.*f", std::min(decimals, 15), value);
  } else {
    const int digits =
        static_cast<int>(std::floor(std::log10(largest)) - std::floor(std::log10(step)));
    std::snprintf(text, sizeof text, "%.*e", std::clamp(digits, 0, 15), value);
  }
  return text;
}

/// Labelled ticks at the multiples of a nice step inside the range.
std::vector<Tick> linear_ticks(const Range& range) {
  const double step = nice_step(range.hi - range.lo);
  const double first = std::ceil(range.lo / step - 1e-9);
  const double last = std::floor(range.hi / step + 1e-9);
  const double largest = std::max(std::abs(range.lo), std::abs(range.hi));
  const int count = static_cast<int>(std::min<double>(last - first, kMaxTicks));
  std::vector<Tick> ticks;
  for (int k = 0; k <= count; ++k) {
    double value = (first + k) * step;
    if (std::abs(value) < 1e-9 * step) value = 0;  // no "-0.0"
    ticks.push_back({value, linear_label(value, step, largest), true});
  }
  return ticks;
}

/// Where `value` lies along [lo, hi]: 0 at lo, 1 at hi (in log10 on logarithmic axes).
double axis_fraction(double value, double lo, double hi, bool log) {
  if (log) return (std::log10(value) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
  return (value - lo) / (hi - lo);
}

/// Selects the plot font at `size` pixels.
void set_font(cairo_t* cr, double size, bool bold = false) {
  cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

/// Advance width of `text` in the current font.
double text_width(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  return extents.x_advance;
}

/// Ascent + descent of the current font.
double font_height(cairo_t* cr) {
  cairo_font_extents_t extents;
  cairo_font_extents(cr, &extents);
  return extents.ascent + extents.descent;
}

/// Height of a line of text at `size` pixels (0 for an empty text, which is left out).
double line_height(cairo_t* cr, const std::string& text, double size, bool bold = false) {
  if (text.empty()) return 0;
  set_font(cr, size, bold);
  return font_height(cr);
}

/// Font sizes in pixels.
struct Fonts {
  double tick, label, title, legend;
};

/// Base font sizes (12, 14, 16, 12 px at 900 × 600) scaled with the image's smaller relative
/// side, within [0.6, 3] times.
Fonts fonts_for(const PlotSpec& spec) {
  const double scale =
      std::clamp(std::min(spec.width / kBaseWidth, spec.height / kBaseHeight), 0.6, 3.0);
  return {12 * scale, 14 * scale, 16 * scale, 12 * scale};
}

/// Widest tick label at font size `size`.
double widest_tick_label(cairo_t* cr, const std::vector<Tick>& ticks, double size) {
  set_font(cr, size);
  double widest = 0;
  for (const Tick& tick : ticks) widest = std::max(widest, text_width(cr, tick.label));
  return widest;
}

/// Whether the plot has a legend: when some series has a label.
bool has_legend(const PlotSpec& spec) {
  return std::any_of(spec.series.begin(), spec.series.end(),
                     [](const PlotSeries& s) { return !s.label.empty(); });
}

/// Natural legend box width (0 without a legend).
double legend_width(cairo_t* cr, const PlotSpec& spec, double size) {
  if (!has_legend(spec)) return 0;
  set_font(cr, size);
  double widest = 0;
  for (const PlotSeries& s : spec.series) widest = std::max(widest, text_width(cr, s.label));
  return 2 * kLegendPad + kSwatch + kLegendPad + widest;
}

/// Height of one legend row at font size `size`.
double legend_row_height(cairo_t* cr, double size) {
  set_font(cr, size);
  return std::max(font_height(cr) + 4, 2 * kMarkerRadius + 6);
}

/// A laid-out plot: the frame plus what is drawn around it.
struct Layout {
  PlotFrame frame;
  std::vector<Tick> x_ticks, y_ticks;
  Fonts fonts;
  double legend_width = 0;
};

/// Pixel margins around the plot area (capped so the plot area keeps 40 % of the image).
struct Margins {
  double left, right, top, bottom;
};

/// The label of the last labelled tick ("" if none).
std::string last_label(const std::vector<Tick>& ticks) {
  for (auto tick = ticks.rbegin(); tick != ticks.rend(); ++tick)
    if (tick->major) return tick->label;
  return "";
}

/// Margins with room for the texts of `spec` and the tick labels of `layout`.
Margins plot_margins(cairo_t* cr, const PlotSpec& spec, const Layout& layout) {
  const Fonts& fonts = layout.fonts;
  const double tick_height = line_height(cr, "0", fonts.tick);
  const double y_label = line_height(cr, spec.y_label, fonts.label);
  const double x_label = line_height(cr, spec.x_label, fonts.label);
  const double title = line_height(cr, spec.title, fonts.title, true);
  set_font(cr, fonts.tick);
  const double last_x_label = text_width(cr, last_label(layout.x_ticks));
  Margins m;
  m.left = kPad + (y_label > 0 ? y_label + kLabelGap : 0) +
           widest_tick_label(cr, layout.y_ticks, fonts.tick) + kTickLength + kTickGap;
  m.right = std::max(kPad + (layout.legend_width > 0 ? layout.legend_width + kLegendGap : 0),
                     kPad + last_x_label / 2);
  m.top = kPad + std::max(title > 0 ? title + kLabelGap : 0, tick_height / 2);
  m.bottom = kPad + (x_label > 0 ? x_label + kLabelGap : 0) + tick_height + kTickLength + kTickGap;
  const double w = spec.width, h = spec.height;
  return {std::min(m.left, 0.3 * w), std::min(m.right, 0.3 * w), std::min(m.top, 0.3 * h),
          std::min(m.bottom, 0.3 * h)};
}

/// Ranges, ticks and plot area of `spec`, measuring text with `cr`.
Layout compute_layout(cairo_t* cr, const PlotSpec& spec) {
  validate(spec);
  const std::array<Range, 2> data = data_ranges(spec);
  if (data[0].empty())
    fail(Status::invalid_argument,
         "line plot: no drawable point (every point is non-finite or ≤ 0 on a log axis)");
  Layout layout;
  PlotFrame& f = layout.frame;
  const Range x = axis_range(data[0], spec.log_x, "x");
  const Range y = axis_range(data[1], spec.log_y, "y");
  f.x_min = x.lo, f.x_max = x.hi, f.y_min = y.lo, f.y_max = y.hi;
  f.log_x = spec.log_x, f.log_y = spec.log_y;
  layout.x_ticks = spec.log_x ? log_ticks(x) : linear_ticks(x);
  layout.y_ticks = spec.log_y ? log_ticks(y) : linear_ticks(y);
  layout.fonts = fonts_for(spec);
  layout.legend_width =
      std::min(legend_width(cr, spec, layout.fonts.legend), 0.3 * spec.width - kLegendGap - kPad);
  const Margins m = plot_margins(cr, spec, layout);
  f.left = std::round(m.left);
  f.right = std::round(spec.width - m.right);
  f.top = std::round(m.top);
  f.bottom = std::round(spec.height - m.bottom);
  check_cairo(cairo_status(cr), "line plot layout");
  return layout;
}

/// Sets the source colour.
void set_color(cairo_t* cr, const Rgb& c) {
  cairo_set_source_rgb(cr, c[0], c[1], c[2]);
}

/// The centre of the pixel containing coordinate v, for crisp 1-pixel lines.
double crisp(double v) {
  return std::floor(v) + 0.5;
}

enum class Align { start, center, end };

/// Draws `text` in the current font with its box aligned to (x, y): horizontally by `h`,
/// vertically by `v` (start = top).
void draw_text(cairo_t* cr, const std::string& text, double x, double y, Align h, Align v) {
  if (text.empty()) return;
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  const double fx = h == Align::start ? 0 : h == Align::center ? 0.5 : 1;
  const double fy = v == Align::start ? 0 : v == Align::center ? 0.5 : 1;
  cairo_move_to(cr, x - fx * e.x_advance, y - e.y_bearing - fy * e.height);
  cairo_show_text(cr, text.c_str());
}

/// Grid lines at every tick, minor ones lighter, within the plot area.
void draw_grid(cairo_t* cr, const Layout& layout) {
  const PlotFrame& f = layout.frame;
  cairo_set_line_width(cr, 1);
  for (const bool major : {false, true}) {
    for (const Tick& t : layout.x_ticks) {
      if (t.major != major) continue;
      const double px = crisp(f.to_pixel(t.value, f.y_min)[0]);
      cairo_move_to(cr, px, f.top);
      cairo_line_to(cr, px, f.bottom);
    }
    for (const Tick& t : layout.y_ticks) {
      if (t.major != major) continue;
      const double py = crisp(f.to_pixel(f.x_min, t.value)[1]);
      cairo_move_to(cr, f.left, py);
      cairo_line_to(cr, f.right, py);
    }
    set_color(cr, major ? kMajorGrid : kMinorGrid);
    cairo_stroke(cr);
  }
}

/// The polyline through the drawable points of `s`, broken at skipped points. Each piece
/// starts with a zero-length segment, so that an isolated point still shows as a round dot.
void trace_polyline(cairo_t* cr, const PlotFrame& f, const PlotSeries& s) {
  bool pen_down = false;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!drawable(s.x[i], s.y[i], f.log_x, f.log_y)) {
      pen_down = false;
      continue;
    }
    const auto p = f.to_pixel(s.x[i], s.y[i]);
    if (!pen_down) cairo_move_to(cr, p[0], p[1]);
    cairo_line_to(cr, p[0], p[1]);
    pen_down = true;
  }
}

/// Adds a marker circle at (x, y) to the path.
void trace_marker(cairo_t* cr, double x, double y) {
  cairo_new_sub_path(cr);
  cairo_arc(cr, x, y, kMarkerRadius, 0, 2 * kPi);
}

/// Lines and markers of one series in its colour, clipped to the plot area (plus a marker).
void draw_series(cairo_t* cr, const PlotFrame& f, const PlotSeries& s, const Rgb& color) {
  cairo_save(cr);
  const double margin = kMarkerRadius + 1;
  cairo_rectangle(cr, f.left - margin, f.top - margin, f.right - f.left + 2 * margin,
                  f.bottom - f.top + 2 * margin);
  cairo_clip(cr);
  set_color(cr, color);
  if (s.lines) {
    trace_polyline(cr, f, s);
    cairo_set_line_width(cr, kLineWidth);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_stroke(cr);
  }
  if (s.markers) {
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (drawable(s.x[i], s.y[i], f.log_x, f.log_y)) {
        const auto p = f.to_pixel(s.x[i], s.y[i]);
        trace_marker(cr, p[0], p[1]);
      }
    cairo_fill(cr);
  }
  cairo_restore(cr);
}

/// The plot area's border, tick marks and tick labels.
void draw_axes(cairo_t* cr, const Layout& layout) {
  const PlotFrame& f = layout.frame;
  set_color(cr, kText);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, f.left - 0.5, f.top - 0.5, f.right - f.left + 1, f.bottom - f.top + 1);
  set_font(cr, layout.fonts.tick);
  for (const Tick& t : layout.x_ticks) {
    if (!t.major) continue;
    const double px = crisp(f.to_pixel(t.value, f.y_min)[0]);
    cairo_move_to(cr, px, f.bottom);
    cairo_line_to(cr, px, f.bottom + kTickLength);
  }
  for (const Tick& t : layout.y_ticks) {
    if (!t.major) continue;
    const double py = crisp(f.to_pixel(f.x_min, t.value)[1]);
    cairo_move_to(cr, f.left, py);
    cairo_line_to(cr, f.left - kTickLength, py);
  }
  cairo_stroke(cr);
  for (const Tick& t : layout.x_ticks)
    draw_text(cr, t.label, crisp(f.to_pixel(t.value, f.y_min)[0]),
              f.bottom + kTickLength + kTickGap, Align::center, Align::start);
  for (const Tick& t : layout.y_ticks)
    draw_text(cr, t.label, f.left - kTickLength - kTickGap, crisp(f.to_pixel(f.x_min, t.value)[1]),
              Align::end, Align::center);
}

/// Shortens `text` with a trailing "…" until it fits `width` in the current font.
std::string fit_text(cairo_t* cr, std::string text, double width) {
  if (text_width(cr, text) <= width) return text;
  while (!text.empty() && text_width(cr, text + "…") > width) {
    while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80)
      text.pop_back();  // UTF-8 continuation bytes, then the lead byte
    if (!text.empty()) text.pop_back();
  }
  return text + "…";
}

/// Title above the plot area (kept inside the image), x label under the tick labels, y label
/// rotated on the left; each shortened to fit the image.
void draw_labels(cairo_t* cr, const PlotSpec& spec, const Layout& layout) {
  const PlotFrame& f = layout.frame;
  set_color(cr, kText);
  const double mid_x = (f.left + f.right) / 2;
  set_font(cr, layout.fonts.title, true);
  const std::string title = fit_text(cr, spec.title, spec.width - 2 * kPad);
  const double half = text_width(cr, title) / 2;
  draw_text(cr, title, std::clamp(mid_x, kPad + half, spec.width - kPad - half), kPad,
            Align::center, Align::start);
  set_font(cr, layout.fonts.label);
  draw_text(cr, fit_text(cr, spec.x_label, spec.width - 2 * kPad), mid_x, spec.height - kPad,
            Align::center, Align::end);
  cairo_save(cr);
  cairo_translate(cr, kPad, (f.top + f.bottom) / 2);
  cairo_rotate(cr, -kPi / 2);
  draw_text(cr, fit_text(cr, spec.y_label, f.bottom - f.top + 2 * kPad), 0, 0, Align::center,
            Align::start);
  cairo_restore(cr);
}

/// One legend row: line sample and/or marker in the series colour, then the label.
void draw_legend_row(cairo_t* cr, const PlotSeries& s, const Rgb& color, double x, double y,
                     double text_room) {
  set_color(cr, color);
  if (s.lines) {
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, x + kSwatch, y);
    cairo_set_line_width(cr, kLineWidth);
    cairo_stroke(cr);
  }
  if (s.markers) {
    trace_marker(cr, x + kSwatch / 2, y);
    cairo_fill(cr);
  }
  set_color(cr, kText);
  draw_text(cr, fit_text(cr, s.label, text_room), x + kSwatch + kLegendPad, y, Align::start,
            Align::center);
}

/// The legend box right of the plot area, one row per series (all listed).
void draw_legend(cairo_t* cr, const PlotSpec& spec, const Layout& layout) {
  if (layout.legend_width <= 0) return;
  const double row = legend_row_height(cr, layout.fonts.legend);
  const double x = std::round(layout.frame.right + kLegendGap);
  const double y = layout.frame.top;
  const double height = 2 * kLegendPad + row * static_cast<double>(spec.series.size());
  cairo_rectangle(cr, x + 0.5, y + 0.5, std::round(layout.legend_width), std::round(height));
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_fill_preserve(cr);
  set_color(cr, kLegendBorder);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  set_font(cr, layout.fonts.legend);
  const double text_room = layout.legend_width - 3 * kLegendPad - kSwatch;
  for (std::size_t k = 0; k < spec.series.size(); ++k)
    draw_legend_row(cr, spec.series[k], series_color(static_cast<int>(k)), x + kLegendPad,
                    y + kLegendPad + row * (static_cast<double>(k) + 0.5), text_room);
}

/// Everything, on a white background.
void draw_plot(cairo_t* cr, const PlotSpec& spec, const Layout& layout) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  draw_grid(cr, layout);
  for (std::size_t k = 0; k < spec.series.size(); ++k)
    draw_series(cr, layout.frame, spec.series[k], series_color(static_cast<int>(k)));
  draw_axes(cr, layout);
  draw_labels(cr, spec, layout);
  draw_legend(cr, spec, layout);
}

/// Writes the surface to `path` + ".partial" and renames it to `path`; on failure removes the
/// partial file and throws Error(io_error) naming the path.
void save_png(cairo_surface_t* surface, const std::string& path) {
  const std::string partial = path + ".partial";
  cairo_surface_flush(surface);
  check_cairo(cairo_surface_status(surface), path);
  const cairo_status_t status = cairo_surface_write_to_png(surface, partial.c_str());
  if (status != CAIRO_STATUS_SUCCESS) {
    std::remove(partial.c_str());
    fail(Status::io_error,
         path + ": cannot write the PNG file (cairo: " + cairo_status_to_string(status) + ")");
  }
  if (std::rename(partial.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(partial.c_str());
    fail(Status::io_error, path + ": cannot move the PNG file into place (" + reason + ")");
  }
}

}  // namespace

std::array<double, 2> PlotFrame::to_pixel(double x, double y) const {
  return {left + axis_fraction(x, x_min, x_max, log_x) * (right - left),
          bottom - axis_fraction(y, y_min, y_max, log_y) * (bottom - top)};
}

PlotFrame layout_plot(const PlotSpec& spec) {
  const Canvas scratch = make_canvas(1, 1, "line plot layout");
  return compute_layout(scratch.cr.get(), spec).frame;
}

void write_line_plot_png(const PlotSpec& spec, const std::string& path) {
  validate(spec);  // before allocating an image of the requested size
  const Canvas canvas = make_canvas(spec.width, spec.height, path);
  cairo_t* cr = canvas.cr.get();
  const Layout layout = compute_layout(cr, spec);
  draw_plot(cr, spec, layout);
  check_cairo(cairo_status(cr), path);
  save_png(canvas.surface.get(), path);
}

std::array<double, 3> series_color(int k) {
  // Okabe & Ito (2008), "Color Universal Design": blue, vermillion, bluish green, reddish
  // purple, orange, sky blue, black, yellow (last: it is faint on white).
  static constexpr std::array<std::array<int, 3>, 8> kPalette = {{{0, 114, 178},
                                                                  {213, 94, 0},
                                                                  {0, 158, 115},
                                                                  {204, 121, 167},
                                                                  {230, 159, 0},
                                                                  {86, 180, 233},
                                                                  {0, 0, 0},
                                                                  {240, 228, 66}}};
  const int n = static_cast<int>(kPalette.size());
  const auto& c = kPalette[((k % n) + n) % n];
  return {c[0] / 255.0, c[1] / 255.0, c[2] / 255.0};
}

}  // namespace progsim
