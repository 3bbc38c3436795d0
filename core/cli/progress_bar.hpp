#pragma once
/// @file A terminal progress bar for long CLI runs (stderr).
#include <cstdio>
#include <string>

namespace progsim::cli {

/// Draws "label [#####.....] 42/100 ETA 3.1s" on stderr. On a terminal it redraws one line;
/// otherwise (logs, CI) it prints a line at every 10 % so logs stay readable.
class ProgressBar {
 public:
  ProgressBar(std::string label, int total);
  /// Reports that `done` of `total` units are complete.
  void update(int done);
  /// Ends the bar's line.
  void finish();

 private:
  std::string label_;
  int total_;
  int last_decile_ = -1;
  bool interactive_;
  double start_seconds_;
};

/// A core progress callback (fraction in [0, 1]) that draws on the ProgressBar `bar` (of 100
/// units); never cancels.
bool draw_percent(void* bar, double fraction, const char* phase);

}  // namespace progsim::cli
