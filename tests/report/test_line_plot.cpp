/// @file Line plots: written PNGs are read back with cairo and their pixels checked against
/// the layout's data → pixel mapping.
#include <cairo.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "report/line_plot.hpp"
#include "support/expect_error.hpp"

using namespace progsim;
using progsim::test_support::expect_error;
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
using Rgb = std::array<double, 3>;

/// A PNG read back with cairo (ARGB32, opaque).
class Png {
 public:
  explicit Png(const std::string& path)
      : surface_(cairo_image_surface_create_from_png(path.c_str())) {}
  cairo_status_t status() const { return cairo_surface_status(surface_.get()); }
  int width() const { return cairo_image_surface_get_width(surface_.get()); }
  int height() const { return cairo_image_surface_get_height(surface_.get()); }

  /// Colour of the pixel (x, y) with channels in [0, 1].
  Rgb pixel(int x, int y) const {
    const unsigned char* data = cairo_image_surface_get_data(surface_.get());
    const int stride = cairo_image_surface_get_stride(surface_.get());
    std::uint32_t argb;
    std::memcpy(&argb, data + y * stride + 4 * x, sizeof argb);
    return {((argb >> 16) & 0xff) / 255.0, ((argb >> 8) & 0xff) / 255.0, (argb & 0xff) / 255.0};
  }

  /// Colour of the pixel containing the pixel coordinate p.
  Rgb at(const std::array<double, 2>& p) const {
    return pixel(static_cast<int>(std::floor(p[0])), static_cast<int>(std::floor(p[1])));
  }

 private:
  struct Deleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
  };
  std::unique_ptr<cairo_surface_t, Deleter> surface_;
};

/// Whether every channel of a and b differs by at most `tolerance`.
bool near(const Rgb& a, const Rgb& b, double tolerance = 0.1) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(a[c] - b[c]) > tolerance) return false;
  return true;
}

/// Whether a colour is white or a light grey (background or grid).
bool light_grey(const Rgb& c) {
  return c[0] >= 0.8 && std::abs(c[0] - c[1]) < 0.02 && std::abs(c[1] - c[2]) < 0.02;
}

std::string show(const Rgb& c) {
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
         ")";
}

PlotSeries make_series(const std::string& label, std::vector<double> x, std::vector<double> y,
                       bool lines = true, bool markers = true) {
  PlotSeries s;
  s.label = label;
  s.x = std::move(x);
  s.y = std::move(y);
  s.lines = lines;
  s.markers = markers;
  return s;
}

/// Expects every drawable point (x[i], y[i]) of series k to show the series' colour.
void expect_markers(const Png& png, const PlotFrame& frame, const PlotSeries& s, int k) {
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const bool skipped = !std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) ||
                         (frame.log_x && s.x[i] <= 0) || (frame.log_y && s.y[i] <= 0);
    if (skipped) continue;
    const Rgb c = png.at(frame.to_pixel(s.x[i], s.y[i]));
    EXPECT_TRUE(near(c, series_color(k)))
        << "series " << k << " point " << i << " shows " << show(c);
  }
}

/// Frees cairo's font caches after the last test, so that LeakSanitizer (the ASan build runs
/// the tests with detect_leaks=1) reports only leaks of progsim, not cairo's static data.
/// cairo asserts here if a surface or context was never destroyed: a leak check of its own.
class ReleaseCairoCaches : public ::testing::Environment {
 public:
  void TearDown() override { cairo_debug_reset_static_data(); }
};
::testing::Environment* const release_cairo_caches =
    ::testing::AddGlobalTestEnvironment(new ReleaseCairoCaches);

}  // namespace

/// Tests get their own fresh directory under the system temporary directory.
class LinePlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device random;
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / ("progsim_line_plot_" + name + "_" +
                                        std::to_string(random()) + std::to_string(random()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code error;
    fs::remove_all(dir_, error);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  bool dir_is_empty() const { return fs::is_empty(dir_); }

  fs::path dir_;
};

namespace {

/// Accuracy-vs-time style data: two series on log-log axes.
PlotSpec two_series_log_log() {
  PlotSpec spec;
  spec.title = "Accuracy vs time";
  spec.x_label = "time (s)";
  spec.y_label = "relative error";
  spec.log_x = spec.log_y = true;
  spec.series.push_back(
      make_series("progressive", {0.02, 0.05, 0.2, 0.9, 4.0}, {0.4, 0.12, 0.03, 0.008, 0.003}));
  spec.series.push_back(make_series("direct", {0.3, 2.5, 11.0}, {0.2, 0.02, 0.004}, false, true));
  return spec;
}

}  // namespace

TEST_F(LinePlotTest, WritesAPngOfTheRequestedSize) {
  PlotSpec spec = two_series_log_log();
  spec.width = 640;
  spec.height = 480;
  const std::string file = path("plot.png");
  write_line_plot_png(spec, file);
  const Png png(file);
  ASSERT_EQ(png.status(), CAIRO_STATUS_SUCCESS) << cairo_status_to_string(png.status());
  EXPECT_EQ(png.width(), 640);
  EXPECT_EQ(png.height(), 480);
  EXPECT_FALSE(fs::exists(file + ".partial"));
}

TEST_F(LinePlotTest, ReplacesAnExistingFile) {
  const std::string file = path("plot.png");
  std::ofstream(file) << "old contents";
  write_line_plot_png(two_series_log_log(), file);
  const Png png(file);
  ASSERT_EQ(png.status(), CAIRO_STATUS_SUCCESS);
  EXPECT_EQ(png.width(), 900);
  EXPECT_EQ(png.height(), 600);
}

TEST_F(LinePlotTest, MarkersLandWhereTheFrameMapsThem) {
  PlotSpec spec;
  spec.title = "markers";
  spec.series.push_back(make_series("a", {1.2, 2, 3, 3.7}, {1.3, 3, 2, 3.6}, false, true));
  spec.series.push_back(make_series("b", {1.6, 3.3}, {3.3, 1.6}, false, true));
  const std::string file = path("markers.png");
  write_line_plot_png(spec, file);
  const Png png(file);
  ASSERT_EQ(png.status(), CAIRO_STATUS_SUCCESS);
  const PlotFrame frame = layout_plot(spec);
  ASSERT_LT(frame.left, frame.right);
  ASSERT_LT(frame.top, frame.bottom);
  for (int k = 0; k < 2; ++k) expect_markers(png, frame, spec.series[k], k);
  // Far from every point (more than 0.5 data units, about 100 pixels): background or grid.
  for (const auto& [x, y] : {std::array<double, 2>{2.5, 1.5}, {2.5, 3.4}, {1.2, 2.3}}) {
    const Rgb c = png.at(frame.to_pixel(x, y));
    EXPECT_TRUE(light_grey(c)) << "(" << x << ", " << y << ") shows " << show(c);
  }
}

TEST_F(LinePlotTest, LinesFollowThePointOrderAndBreakAtSkippedPoints) {
  PlotSpec spec;
  spec.series.push_back(make_series("turn", {1, 3, 3}, {1, 1, 3}, true, false));
  spec.series.push_back(make_series("broken", {1, 2, 3}, {2.5, kNaN, 2.5}, true, false));
  const std::string file = path("lines.png");
  write_line_plot_png(spec, file);
  const Png png(file);
  ASSERT_EQ(png.status(), CAIRO_STATUS_SUCCESS);
  const PlotFrame frame = layout_plot(spec);
  EXPECT_TRUE(near(png.at(frame.to_pixel(2, 1)), series_color(0)));  // (1,1) → (3,1)
  EXPECT_TRUE(near(png.at(frame.to_pixel(3, 2)), series_color(0)));  // (3,1) → (3,3)
  EXPECT_TRUE(light_grey(png.at(frame.to_pixel(2, 2))));             // no (1,1) → (3,3) shortcut
  EXPECT_TRUE(light_grey(png.at(frame.to_pixel(2, 2.5))));  // the NaN point breaks the line
}

TEST_F(LinePlotTest, IsolatedPointsOfALinesOnlySeriesShowAsDots) {
  PlotSpec spec;
  spec.series.push_back(make_series("dots", {1, 2, 3}, {1, kNaN, 2}, true, false));
  const std::string file = path("dots.png");
  write_line_plot_png(spec, file);
  const Png png(file);
  ASSERT_EQ(png.status(), CAIRO_STATUS_SUCCESS);
  const PlotFrame frame = layout_plot(spec);
  for (const int i : {0, 2}) {
    // A 2-pixel dot covers only part of the pixel under its centre: blue (red channel 0)
    // blended with white (1), but clearly more blue than the background or grid.
    const Rgb c = png.at(frame.to_pixel(spec.series[0].x[i], spec.series[0].y[i]));
    EXPECT_EQ(series_color(0)[0], 0.0);
    EXPECT_LT(c[0], 0.6) << "point " << i << " shows " << show(c);
  }
}

TEST(LinePlotLayout, LogAxesSpanWholeDecadesAroundTheData) {
  const PlotSpec spec = two_series_log_log();  // x in [0.02, 11], y in [0.003, 0.4]
  const PlotFrame f = layout_plot(spec);
  EXPECT_TRUE(f.log_x && f.log_y);
  EXPECT_NEAR(f.x_min, 1e-2, 1e-2 * 1e-12);
  EXPECT_NEAR(f.x_max, 1e2, 1e2 * 1e-12);
  EXPECT_NEAR(f.y_min, 1e-3, 1e-3 * 1e-12);
  EXPECT_NEAR(f.y_max, 1e0, 1e-12);
  // Decades are equally spaced: the corners map to the plot area's corners, 10^mid to its centre.
  const auto bottom_left = f.to_pixel(f.x_min, f.y_min);
  const auto top_right = f.to_pixel(f.x_max, f.y_max);
  const auto centre = f.to_pixel(1.0, std::pow(10.0, -1.5));
  EXPECT_NEAR(bottom_left[0], f.left, 1e-9);
  EXPECT_NEAR(bottom_left[1], f.bottom, 1e-9);
  EXPECT_NEAR(top_right[0], f.right, 1e-9);
  EXPECT_NEAR(top_right[1], f.top, 1e-9);
  EXPECT_NEAR(centre[0], (f.left + f.right) / 2, 1e-9);
  EXPECT_NEAR(centre[1], (f.top + f.bottom) / 2, 1e-9);
}

TEST(LinePlotLayout, LinearAxesArePaddedToRoundNumbers) {
  PlotSpec spec;
  spec.series.push_back(make_series("s", {0.3, 9.7}, {-2.2, 13}));
  const PlotFrame f = layout_plot(spec);
  EXPECT_FALSE(f.log_x || f.log_y);
  EXPECT_NEAR(f.x_min, 0, 1e-12);
  EXPECT_NEAR(f.x_max, 10, 1e-12);
  EXPECT_NEAR(f.y_min, -3, 1e-12);
  EXPECT_NEAR(f.y_max, 14, 1e-12);
}

TEST(LinePlotLayout, PlotAreaLeavesRoomForTextAndLegend) {
  PlotSpec spec = two_series_log_log();
  const PlotFrame f = layout_plot(spec);
  EXPECT_GT(f.left, 40);                  // y tick labels and y label
  EXPECT_LT(f.right, spec.width - 80);    // legend
  EXPECT_GT(f.top, 20);                   // title
  EXPECT_LT(f.bottom, spec.height - 30);  // x tick labels and x label
  EXPECT_GT(f.right - f.left, 0.5 * spec.width);
  EXPECT_GT(f.bottom - f.top, 0.6 * spec.height);
}

TEST_F(LinePlotTest, NonPositiveValuesOnALogAxisAreSkipped) {
  PlotSpec spec;
  spec.log_x = spec.log_y = true;
  spec.series.push_back(make_series("s", {2, 3, 4, 5, 6, 1e6, 1e-6},
                                    {0.02, 0, 0.05, -1, 0.5, kNaN, kInf}, false, true));
  const PlotFrame f = layout_plot(spec);
  EXPECT_NEAR(f.x_min, 1, 1e-12);  // neither 1e6 nor 1e-6: their y is not finite
  EXPECT_NEAR(f.x_max, 10, 1e-12);
  EXPECT_NEAR(f.y_min, 1e-2, 1e-14);  // 0 and -1 are skipped
  EXPECT_NEAR(f.y_max, 1, 1e-12);
  const std::string file = path("log.png");
  write_line_plot_png(spec, file);
  const Png png(file);
  ASSERT_EQ(png.status(), CAIRO_STATUS_SUCCESS);
  expect_markers(png, f, spec.series[0], 0);
}

TEST_F(LinePlotTest, SeriesWithoutDrawablePointsIsStillInTheLegend) {
  PlotSpec spec;
  spec.series.push_back(make_series("drawn", {1, 2}, {1, 2}));
  spec.series.push_back(make_series("all skipped", {kNaN, 1}, {1, kInf}));
  const std::string file = path("legend.png");
  write_line_plot_png(spec, file);
  const Png png(file);
  ASSERT_EQ(png.status(), CAIRO_STATUS_SUCCESS);
  const PlotFrame f = layout_plot(spec);
  std::array<int, 2> legend_pixels = {0, 0};
  for (int y = 0; y < png.height(); ++y)
    for (int x = static_cast<int>(f.right) + 2; x < png.width(); ++x)
      for (int k = 0; k < 2; ++k) legend_pixels[k] += near(png.pixel(x, y), series_color(k), 0.02);
  EXPECT_GT(legend_pixels[0], 20);
  EXPECT_GT(legend_pixels[1], 20);
}

TEST_F(LinePlotTest, SinglePointPlotsAreValid) {
  PlotSpec linear;
  linear.series.push_back(make_series("one", {2}, {5}));
  PlotFrame f = layout_plot(linear);
  EXPECT_LT(f.x_min, 2);
  EXPECT_GT(f.x_max, 2);
  EXPECT_LT(f.y_min, 5);
  EXPECT_GT(f.y_max, 5);
  PlotSpec at_zero;
  at_zero.series.push_back(make_series("zero", {0}, {0}));
  f = layout_plot(at_zero);
  EXPECT_LE(f.x_min, -1);
  EXPECT_GE(f.x_max, 1);
  PlotSpec log;
  log.log_x = log.log_y = true;
  log.series.push_back(make_series("decade", {1e-2}, {1e-3}));
  f = layout_plot(log);
  EXPECT_NEAR(f.x_min, 1e-3, 1e-15);
  EXPECT_NEAR(f.x_max, 1e-1, 1e-13);
  EXPECT_NEAR(f.y_min, 1e-4, 1e-16);
  EXPECT_NEAR(f.y_max, 1e-2, 1e-14);
  for (const PlotSpec* spec : {&linear, &at_zero, &log}) {
    const std::string file = path("single.png");
    write_line_plot_png(*spec, file);
    const Png png(file);
    ASSERT_EQ(png.status(), CAIRO_STATUS_SUCCESS);
    EXPECT_EQ(png.width(), spec->width);
    expect_markers(png, layout_plot(*spec), spec->series[0], 0);
  }
}

TEST_F(LinePlotTest, InvalidSpecsAreRejectedWithoutWritingAFile) {
  const std::string file = path("plot.png");
  const auto rejects = [&](const PlotSpec& spec, const std::string& needle) {
    expect_error([&] { write_line_plot_png(spec, file); }, Status::invalid_argument, {needle});
    expect_error([&] { layout_plot(spec); }, Status::invalid_argument, {needle});
  };
  rejects(PlotSpec{}, "no series");
  PlotSpec mismatched;
  mismatched.series.push_back(make_series("level 2", {1, 2, 3}, {1, 2}));
  rejects(mismatched, "level 2");
  for (const auto& [w, h] : {std::array<int, 2>{0, 600}, {900, 99}, {10001, 600}, {900, -5}}) {
    PlotSpec bad_size = two_series_log_log();
    bad_size.width = w;
    bad_size.height = h;
    rejects(bad_size, "outside [100, 10000]");
  }
  PlotSpec non_finite;
  non_finite.series.push_back(make_series("nan", {kNaN, kInf, 1}, {1, 2, -kInf}));
  rejects(non_finite, "no drawable point");
  PlotSpec non_positive;
  non_positive.log_y = true;
  non_positive.series.push_back(make_series("zero", {1, 2}, {0, -1}));
  rejects(non_positive, "no drawable point");
  EXPECT_TRUE(dir_is_empty());
}

TEST_F(LinePlotTest, UnwritablePathIsAnIoErrorLeavingNoFile) {
  const std::string file = path("missing_directory/plot.png");
  expect_error([&] { write_line_plot_png(two_series_log_log(), file); }, Status::io_error, {file});
  EXPECT_FALSE(fs::exists(file));
  EXPECT_FALSE(fs::exists(file + ".partial"));
  EXPECT_TRUE(dir_is_empty());
}

TEST_F(LinePlotTest, FailedRenameRemovesThePartialFile) {
  const std::string target = path("a_directory");  // a PNG cannot replace a directory
  fs::create_directory(target);
  fs::create_directory(target + "/keep");  // a non-empty directory: rename(2) always fails
  expect_error([&] { write_line_plot_png(two_series_log_log(), target); }, Status::io_error,
               {target});
  EXPECT_TRUE(fs::is_directory(target + "/keep"));
  EXPECT_FALSE(fs::exists(target + ".partial"));
}

TEST(LinePlotColors, PaletteIsDistinctAndCycles) {
  for (int k = 0; k < 8; ++k) {
    for (const double c : series_color(k)) {
      EXPECT_GE(c, 0);
      EXPECT_LE(c, 1);
    }
    for (int j = 0; j < k; ++j) EXPECT_FALSE(near(series_color(j), series_color(k)));
    EXPECT_EQ(series_color(k), series_color(k + 8));
    EXPECT_EQ(series_color(k - 8), series_color(k));
    EXPECT_FALSE(light_grey(series_color(k))) << k;  // never mistaken for background or grid
  }
}
