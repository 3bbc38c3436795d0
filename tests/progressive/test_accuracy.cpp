// The accuracy-vs-time report: progressive and direct rows for every level, errors against the
// converged finest solution, CSV, Markdown and PNG files, and its refusals.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "progressive/accuracy.hpp"
#include "progressive/progressive_test_scenes.hpp"

using namespace progsim;
using namespace progsim::test_support;
namespace fs = std::filesystem;

namespace {

Scene small_plate() {
  Scene scene = buckling_plate(12, 1e-4, 4);  // 169 vertices
  scene.progressive.level_vertices = {25, 60};
  return scene;
}

const AccuracyReport& plate_report() {
  static const AccuracyReport report = run_accuracy(small_plate());
  return report;
}

}  // namespace

TEST(Accuracy, OneRowPerLevelAndMethodWithErrorsAgainstTheConvergedFinest) {
  const AccuracyReport& r = plate_report();
  ASSERT_EQ(r.rows.size(), 6u);
  const std::vector<int> sizes = {25, 60, 169};
  for (int k = 0; k < 6; ++k) {
    const AccuracyRow& row = r.rows[k];
    EXPECT_EQ(row.method, k < 3 ? AccuracyRow::Method::progressive : AccuracyRow::Method::direct);
    EXPECT_EQ(row.level, k % 3);
    EXPECT_EQ(row.vertices, sizes[k % 3]);
    EXPECT_GT(row.seconds, 0.0);
    EXPECT_GT(row.newton_iterations, 0);
    EXPECT_TRUE(std::isfinite(row.error_rms) && std::isfinite(row.error_max));
    EXPECT_LE(row.error_rms, row.error_max);
  }
  EXPECT_EQ(r.rows[2].error_max, 0.0);              // the reference itself
  EXPECT_GT(r.rows[0].error_max, 0.0);              // a coarse preview is not exact
  EXPECT_LT(r.rows[0].seconds, r.rows[1].seconds);  // progressive times are cumulative
  EXPECT_LT(r.rows[1].seconds, r.rows[2].seconds);
  EXPECT_EQ(r.rows[0].refine_seconds, 0.0);
  EXPECT_GT(r.rows[1].refine_seconds, 0.0);
  EXPECT_LT(r.rows[5].error_max, 1e-3);           // direct finest: the same buckled branch
  EXPECT_NEAR(r.diagonal, std::sqrt(2.0), 1e-3);  // the plate's bump adds 0.1 mm of height
}

TEST(Accuracy, WritesCsvMarkdownAndPngPlots) {
  const fs::path dir = fs::temp_directory_path() / "progsim_accuracy_report";
  fs::remove_all(dir);
  write_accuracy_report(plate_report(), dir.string());
  const std::string csv = accuracy_csv(plate_report());
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7);
  EXPECT_EQ(csv.rfind("direct,2,169,", std::string::npos) != std::string::npos, true);
  const std::string md = accuracy_markdown(plate_report());
  EXPECT_NE(md.find("| method | level | vertices |"), std::string::npos);
  EXPECT_NE(md.find("x faster"), std::string::npos);
  EXPECT_EQ(md.find("Obstacles:"), std::string::npos);  // no progressive collision object
  for (const char* png : {"error_vs_time.png", "error_by_level.png", "time_by_level.png"}) {
    cairo_surface_t* image = cairo_image_surface_create_from_png((dir / png).c_str());
    EXPECT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS) << png;
    EXPECT_EQ(cairo_image_surface_get_width(image), 900) << png;
    cairo_surface_destroy(image);
  }
  EXPECT_TRUE(fs::is_regular_file(dir / "accuracy.csv"));
  EXPECT_TRUE(fs::is_regular_file(dir / "accuracy.md"));
  fs::remove_all(dir);
}

TEST(Accuracy, RefusesScenesWithoutLevels) {
  Scene direct_only = small_plate();
  direct_only.progressive = {};
  try {
    run_accuracy(direct_only);
    FAIL() << "a scene without coarse levels was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::invalid_scene);
  }
}

TEST(Accuracy, ReportsEveryPhaseAndLoadStepAndStopsWhenCancelledInsideASolve) {
  struct Seen {
    std::vector<std::string> phases;
    std::vector<double> fractions;
  } seen;
  auto stop_in_direct_solve = [](void* user, double fraction, const char* phase) {
    auto& s = *static_cast<Seen*>(user);
    s.phases.push_back(phase);
    s.fractions.push_back(fraction);
    return s.phases.back().rfind("direct level 0, load step 1 ", 0) != 0;
  };
  try {
    run_accuracy(small_plate(), 500, stop_in_direct_solve, &seen);
    FAIL() << "cancelling did not stop the run";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::cancelled);
  }
  const std::string of = " of " + std::to_string(small_plate().num_steps());
  std::vector<std::string> expected = {"hierarchy", "progressive level 0"};
  for (int s = 1; s <= small_plate().num_steps(); ++s)
    expected.push_back("progressive level 0, load step " + std::to_string(s) + of);
  for (const char* p : {"progressive level 1", "progressive level 2", "direct level 0"})
    expected.push_back(p);
  expected.push_back("direct level 0, load step 1" + of);  // the last: nothing after cancelling
  EXPECT_EQ(seen.phases, expected);
  for (std::size_t k = 0; k < seen.fractions.size(); ++k) {
    EXPECT_GE(seen.fractions[k], k ? seen.fractions[k - 1] : 0.0) << seen.phases[k];
    EXPECT_LT(seen.fractions[k], 1.0) << seen.phases[k];
  }
}

TEST(Accuracy, RefusesDirectLevelsThatDoNotExistAndNegativeTimeRatios) {
  for (const DirectSolves& direct : {DirectSolves{{3}, 0.0}, DirectSolves{{-1}, 0.0},
                                     DirectSolves{{}, -1.0}, DirectSolves{{}, std::nan("")}}) {
    try {
      run_accuracy(small_plate(), 500, nullptr, nullptr, direct);
      FAIL() << "accepted a direct level or time ratio that makes no sense";
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), Status::invalid_argument) << e.what();
    }
  }
}

TEST(Accuracy, ADirectSolveStoppedAtItsTimeLimitIsReportedUnfinished) {
  const AccuracyReport r = run_accuracy(small_plate(), 500, nullptr, nullptr, {{2, 0}, 1e-9});
  ASSERT_EQ(r.rows.size(), 5u);  // 3 progressive levels, then direct on levels 2 and 0
  EXPECT_EQ(r.rows[3].level, 2);
  EXPECT_EQ(r.rows[4].level, 0);
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(r.rows[k].finished);
  for (int k = 3; k < 5; ++k) {
    EXPECT_FALSE(r.rows[k].finished);
    EXPECT_FALSE(r.rows[k].converged);
    // Past its limit at the first check of its first Newton solve: stopped inside the first
    // load step, not after it.
    EXPECT_EQ(r.rows[k].load_steps, 0);
    EXPECT_EQ(r.rows[k].newton_iterations, 0);
  }
  EXPECT_NE(accuracy_markdown(r).find(">= "), std::string::npos);
  EXPECT_EQ(r.direct_time_limit, 1e-9 * r.rows[2].seconds);  // the pipeline's time
  // Relative to the preview: the limit follows level 0's time instead.
  const AccuracyReport p = run_accuracy(small_plate(), 500, nullptr, nullptr,
                                        {{0}, 1e-9, DirectSolves::TimeBase::preview});
  ASSERT_EQ(p.rows.size(), 4u);
  EXPECT_EQ(p.direct_time_limit, 1e-9 * p.rows[0].seconds);
  EXPECT_FALSE(p.rows[3].finished);
  // Without a limit the same direct solves finish the whole load script.
  const AccuracyReport whole = run_accuracy(small_plate(), 500, nullptr, nullptr, {{0}, 0.0});
  ASSERT_EQ(whole.rows.size(), 4u);
  EXPECT_TRUE(whole.rows[3].finished);
  EXPECT_EQ(whole.rows[3].load_steps, whole.rows[0].load_steps);
}
