// ps_accuracy_*: what accuracy costs in time, progressive against direct on every level.
#include "progressive/accuracy.hpp"

#include <cmath>
#include <string>

#include "api_guard.hpp"
#include "percent_progress.hpp"
#include "progsim.h"
#include "scene/scene_json.hpp"

/// The results of one accuracy run. Immutable once created.
struct ps_accuracy {
  progsim::AccuracyReport report;
};

namespace progsim::capi {
namespace {

constexpr int32_t kAccuracyCookie = 0x50534144;  // "PSAD"

ps_method method_of(AccuracyRow::Method m) {
  return m == AccuracyRow::Method::progressive ? PS_METHOD_PROGRESSIVE : PS_METHOD_DIRECT;
}

/// The direct solves def asks for (nullable: every level, no time limit); rejects defs nobody
/// initialised. The levels and the ratio themselves are checked by run_accuracy.
DirectSolves direct_solves(const ps_accuracy_def* def) {
  if (!def) return {};
  require_initialized(def->internal_cookie, kAccuracyCookie, "ps_accuracy_def");
  const std::vector<int32_t> levels = borrowed_array(def->direct_levels, def->num_direct_levels,
                                                     "direct_levels", "num_direct_levels", 64);
  if (def->direct_time_base != PS_TIME_BASE_PIPELINE &&
      def->direct_time_base != PS_TIME_BASE_PREVIEW)
    fail(Status::invalid_argument,
         "ps_accuracy_def.direct_time_base " +
             std::to_string(static_cast<int>(def->direct_time_base)) +
             " is neither PS_TIME_BASE_PIPELINE nor PS_TIME_BASE_PREVIEW");
  const auto base = def->direct_time_base == PS_TIME_BASE_PREVIEW
                        ? DirectSolves::TimeBase::preview
                        : DirectSolves::TimeBase::pipeline;
  return DirectSolves{{levels.begin(), levels.end()}, def->direct_time_ratio, base};
}

}  // namespace
}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API void ps_accuracy_def_init(ps_accuracy_def* def) {
  if (!def) return;
  *def = ps_accuracy_def{};
  def->internal_cookie = kAccuracyCookie;
}

PS_API int32_t ps_accuracy_run_scene_file(const char* path, const ps_accuracy_def* def,
                                          ps_accuracy** out) {
  return guarded(nullptr, "ps_accuracy_run_scene_file", [&] {
    require(path, "path");
    require(out, "out");
    const DirectSolves direct = direct_solves(def);
    PercentProgress forward{def ? def->progress : nullptr, def ? def->progress_user_data : nullptr};
    auto accuracy = std::make_unique<ps_accuracy>();
    accuracy->report = run_accuracy(load_scene_file(path), 500,
                                    forward.fn ? PercentProgress::call : nullptr, &forward, direct);
    *out = accuracy.release();
  });
}

PS_API void ps_accuracy_destroy(ps_accuracy* accuracy) {
  delete accuracy;
}

PS_API int32_t ps_accuracy_direct_time_limit(const ps_accuracy* accuracy, double* out) {
  return guarded(nullptr, "ps_accuracy_direct_time_limit", [&] {
    require(accuracy, "accuracy");
    require(out, "out");
    *out = accuracy->report.direct_time_limit;
  });
}

PS_API int32_t ps_accuracy_num_rows(const ps_accuracy* accuracy, int32_t* out) {
  return guarded(nullptr, "ps_accuracy_num_rows", [&] {
    require(accuracy, "accuracy");
    require(out, "out");
    *out = static_cast<int32_t>(accuracy->report.rows.size());
  });
}

PS_API int32_t ps_accuracy_get_row(const ps_accuracy* accuracy, int32_t index,
                                   ps_accuracy_row* out) {
  return guarded(nullptr, "ps_accuracy_get_row", [&] {
    require(accuracy, "accuracy");
    require(out, "out");
    const auto n = static_cast<int32_t>(accuracy->report.rows.size());
    if (index < 0 || index >= n)
      api_fail(PS_ERROR_OUT_OF_RANGE,
               "row " + std::to_string(index) + " does not exist (" + std::to_string(n) + " rows)");
    const AccuracyRow& r = accuracy->report.rows[index];
    *out = ps_accuracy_row{method_of(r.method), r.level,      r.vertices,
                           r.newton_iterations, r.seconds,    r.refine_seconds,
                           r.error_rms,         r.error_max,  r.intersecting_pairs,
                           r.converged ? 1 : 0, r.load_steps, r.finished ? 1 : 0};
  });
}

PS_API int32_t ps_accuracy_write(const ps_accuracy* accuracy, const char* dir) {
  return guarded(nullptr, "ps_accuracy_write", [&] {
    require(accuracy, "accuracy");
    require(dir, "dir");
    write_accuracy_report(accuracy->report, dir);
  });
}

}  // extern "C"
