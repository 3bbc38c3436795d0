#pragma once
/// @file Per-term counters: how often each energy term was evaluated and how long it took.
#include <cstdint>
#include <string>

namespace progsim {

/// Counters of one energy term. A term the scene does not enable does not exist, so it
/// has no counters at all: that is how a run proves an unused effect cost nothing.
struct TermStats {
  std::string name;
  std::int64_t value_evaluations = 0;
  std::int64_t gradient_evaluations = 0;
  std::int64_t hessian_evaluations = 0;
  double seconds = 0.0;  ///< wall time spent inside the term

  /// Counter differences self − before (for per-step reports).
  TermStats since(const TermStats& before) const {
    return {name, value_evaluations - before.value_evaluations,
            gradient_evaluations - before.gradient_evaluations,
            hessian_evaluations - before.hessian_evaluations, seconds - before.seconds};
  }
};

}  // namespace progsim
