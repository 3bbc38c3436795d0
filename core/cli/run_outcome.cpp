#include "cli/run_outcome.hpp"

#include <cstdio>

namespace progsim::cli {

void Outcome::fail(const std::string& why) {
  status = "failed";
  message = why;
}

void Outcome::fail(const std::string& where, const Error& e) {
  fail(where + ": " + status_name(e.status()) + ": " + e.what());
  if (e.status() == Status::cancelled) status = "cancelled";
}

std::optional<std::string> solve_failure(const StepRecord& record, const Positions& x) {
  const NewtonStop stop = record.newton.stop;
  if (stop == NewtonStop::non_finite || stop == NewtonStop::factorization_failed)
    return std::string("its Newton solve ended '") + stop_name(stop) + "' after " +
           std::to_string(record.newton.iterations) + " iterations";
  if (!x.allFinite()) return std::string("its state is not finite");
  return std::nullopt;
}

int finish(const Outcome& outcome) {
  if (outcome.ok()) return 0;
  if (outcome.status == "cancelled") {
    std::fprintf(stderr, "progsim: the run was cancelled: %s\n", outcome.message.c_str());
    return kCancelled;
  }
  std::fprintf(stderr, "progsim: the simulation %s: %s\n",
               outcome.status == "failed" ? "failed" : "did not converge", outcome.message.c_str());
  return kSimulationFailed;
}

void add_outcome(nlohmann::json& summary, const Outcome& outcome, bool progressive) {
  summary["status"] = outcome.status;
  summary["message"] = outcome.message;
  summary["last_good_step"] = outcome.last_good_step;
  if (progressive) summary["last_good_level"] = outcome.last_good_level;
}

std::string outcome_line(const Outcome& outcome) {
  return "status: " + outcome.status + (outcome.ok() ? "" : " (" + outcome.message + ")") + "\n";
}

}  // namespace progsim::cli
