#pragma once
/// @file Forwards the core's fractional progress reports to a ps_progress_fn as percent.
#include <cmath>

#include "progsim.h"

namespace progsim::capi {

/// A core progress callback `bool (void* self, double fraction, const char* phase)` that calls
/// `fn(user_data, round(100 · fraction), 100, phase)`; a non-zero answer cancels.
struct PercentProgress {
  ps_progress_fn fn;
  void* user_data;
  static bool call(void* self, double fraction, const char* phase) {
    const auto* forward = static_cast<const PercentProgress*>(self);
    return forward->fn(forward->user_data, static_cast<int32_t>(std::lround(fraction * 100.0)), 100,
                       phase) == 0;
  }
};

}  // namespace progsim::capi
