#pragma once
/// @file How a `progsim run` ended: the outcome summary.json records, and the exit status.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "common/error.hpp"
#include "common/types.hpp"
#include "sim/step_record.hpp"

namespace progsim::cli {

/// Exit status of a run whose simulation failed (a non-finite or unfactorizable solve, an
/// error after the start) or did not converge (the finest level, or a direct run's last
/// step); 2 is bad input, refused before anything is written.
constexpr int kSimulationFailed = 3;

/// Exit status of a run cancelled by SIGINT (Ctrl-C; 128 + 2, as shells report it): it stops
/// at the next load step, settle or refinement, and summary.json says "cancelled".
constexpr int kCancelled = 130;

/// How a run ended: summary.json's "status" ("ok", "not_converged", "failed", "cancelled"),
/// "message" and the last step (and, progressive, level) that ended well.
struct Outcome {
  std::string status = "ok";
  std::string message;
  int last_good_step = 0;    ///< load steps solved without a failure (direct: the last converged)
  int last_good_level = -1;  ///< progressive: the finest level that ended well (−1: none)

  bool ok() const { return status == "ok"; }
  void fail(const std::string& why);
  /// A failure from an Error thrown `where`: "cancelled" for Error(cancelled), else "failed".
  void fail(const std::string& where, const Error& e);
};

/// Why a solve failed outright (non-finite values, no factorization), or nothing: a solve that
/// only stopped at its iteration cap is not a failure here.
std::optional<std::string> solve_failure(const StepRecord& record, const Positions& x);

/// "failed: …" or "not_converged: …" on stderr, and the exit status of a run.
int finish(const Outcome& outcome);

/// Adds "status", "message", "last_good_step" (and, progressive, "last_good_level").
void add_outcome(nlohmann::json& summary, const Outcome& outcome, bool progressive);

/// "status: ok\n", or "status: failed (why)\n".
std::string outcome_line(const Outcome& outcome);

}  // namespace progsim::cli
