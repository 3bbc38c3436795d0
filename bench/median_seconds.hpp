#pragma once
/// @file The benchmarks' timing of a repeated piece of work: the median wall time.
#include <algorithm>
#include <vector>

#include "common/timer.hpp"

namespace progsim::bench {

/// Median wall seconds of `repeats` (≥ 1) calls of `work()`, each after an untimed
/// `prepare()`.
template <class Prepare, class Work>
double median_seconds_after(int repeats, Prepare prepare, Work work) {
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    prepare();
    Timer timer;
    work();
    seconds.push_back(timer.seconds());
  }
  std::nth_element(seconds.begin(), seconds.begin() + repeats / 2, seconds.end());
  return seconds[repeats / 2];
}

/// Median wall seconds of `repeats` (≥ 1) calls of `work()`.
template <class Work>
double median_seconds(int repeats, Work work) {
  return median_seconds_after(
      repeats, [] {}, work);
}

}  // namespace progsim::bench
