#include "cli/progress_bar.hpp"

#include <unistd.h>

#include <chrono>

namespace progsim::cli {
namespace {
double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

ProgressBar::ProgressBar(std::string label, int total)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1),
      interactive_(isatty(fileno(stderr)) != 0),
      start_seconds_(now_seconds()) {}

void ProgressBar::update(int done) {
  const double fraction = static_cast<double>(done) / total_;
  const double elapsed = now_seconds() - start_seconds_;
  const double eta = done > 0 ? elapsed * (total_ - done) / done : 0.0;
  if (interactive_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::fprintf(stderr, "\r%s [%s%s] %d/%d ETA %.1fs ", label_.c_str(),
                 std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(), done,
                 total_, eta);
    std::fflush(stderr);
    return;
  }
  const int decile = static_cast<int>(fraction * 10.0);
  if (decile == last_decile_) return;
  last_decile_ = decile;
  std::fprintf(stderr, "%s %3d%% (%d/%d, %.1fs elapsed, ETA %.1fs)\n", label_.c_str(), decile * 10,
               done, total_, elapsed, eta);
}

void ProgressBar::finish() {
  if (interactive_) std::fprintf(stderr, "\n");
}

bool draw_percent(void* bar, double fraction, const char*) {
  static_cast<ProgressBar*>(bar)->update(static_cast<int>(fraction * 100.0));
  return true;
}

}  // namespace progsim::cli
