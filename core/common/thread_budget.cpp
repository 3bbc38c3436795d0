#include "common/thread_budget.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <string>

#include "common/error.hpp"

#ifdef __linux__
#include <fcntl.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#endif

namespace progsim {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kWindowSeconds = 0.25;
constexpr int kMaxThreads = 1024;

std::atomic<int> fixed_threads{0};
std::atomic<int> sampled_threads{0};  // 0: not sampled yet

#ifdef __linux__
/// Idle seconds of the processors in this process's affinity mask, from /proc/stat, or a
/// negative number when it cannot be read. Reads into a stack buffer: no allocation, so the
/// Newton solver may call it on allocation-free paths.
double idle_seconds_of_allowed_cpus(int* allowed) {
  cpu_set_t mask;
  CPU_ZERO(&mask);
  if (sched_getaffinity(0, sizeof(mask), &mask) != 0) return -1.0;
  *allowed = CPU_COUNT(&mask);
  char text[1 << 15];
  const int file = open("/proc/stat", O_RDONLY | O_CLOEXEC);
  if (file < 0) return -1.0;
  const ssize_t size = read(file, text, sizeof(text) - 1);
  close(file);
  if (size <= 0) return -1.0;
  text[size] = '\0';
  long long idle_ticks = 0;
  // Lines "cpuN user nice system idle iowait ...", after the all-CPU line "cpu  ...".
  for (char* line = text; std::strncmp(line, "cpu", 3) == 0;) {
    char* field = line + 3;
    if (*field != ' ') {
      const long cpu = std::strtol(field, &field, 10);
      long long ticks[5];
      for (long long& t : ticks) t = std::strtoll(field, &field, 10);
      if (cpu >= 0 && cpu < CPU_SETSIZE && CPU_ISSET(cpu, &mask))
        idle_ticks += ticks[3] + ticks[4];  // idle + iowait
    }
    char* next = std::strchr(line, '\n');
    if (!next) break;
    line = next + 1;
  }
  return static_cast<double>(idle_ticks) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

/// This process's CPU time (user + system, all threads) in seconds.
double own_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return t.tv_sec + 1e-6 * t.tv_usec; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

/// The last sample: wall clock, idle seconds of the allowed CPUs, own CPU seconds.
struct LoadSample {
  Clock::time_point wall;
  double idle = -1.0, own = 0.0;
  int allowed = 1;
};

LoadSample take_sample() {
  LoadSample s;
  s.wall = Clock::now();
  s.idle = idle_seconds_of_allowed_cpus(&s.allowed);
  s.own = own_cpu_seconds();
  return s;
}

int threads_between(const LoadSample& a, const LoadSample& b) {
  return free_processors(b.idle - a.idle, b.own - a.own,
                         std::chrono::duration<double>(b.wall - a.wall).count(), b.allowed);
}

std::mutex sample_mutex;
LoadSample last_sample;
#endif

}  // namespace

int free_processors(double idle_seconds, double own_cpu_seconds, double wall_seconds, int allowed) {
  const double free_cpus = (idle_seconds + own_cpu_seconds) / wall_seconds;
  if (!std::isfinite(free_cpus)) return std::max(allowed, 1);
  return std::clamp(static_cast<int>(std::lround(free_cpus)), 1, std::max(allowed, 1));
}

void set_thread_budget(int threads) {
  if (threads < 0 || threads > kMaxThreads)
    fail(Status::invalid_argument, "thread count " + std::to_string(threads) +
                                       " must be 0 (automatic) or 1 to " +
                                       std::to_string(kMaxThreads));
  fixed_threads.store(threads);
}

int thread_budget_setting() {
  return fixed_threads.load();
}

int thread_budget() {
  const int fixed = fixed_threads.load();
  if (fixed > 0) return fixed;
  const int sampled = sampled_threads.load();
  const int cap = omp_get_max_threads();
  return sampled > 0 ? std::min(sampled, cap) : cap;
}

void refresh_thread_budget() {
#ifdef __linux__
  if (fixed_threads.load() > 0) return;
  std::unique_lock<std::mutex> lock(sample_mutex, std::try_to_lock);
  if (!lock.owns_lock()) return;  // another thread is sampling
  const Clock::time_point now = Clock::now();
  if (last_sample.idle >= 0.0 &&
      std::chrono::duration<double>(now - last_sample.wall).count() < kWindowSeconds)
    return;
  const LoadSample sample = take_sample();
  if (sample.idle < 0.0) return;  // no /proc/stat: keep omp_get_max_threads()
  if (last_sample.idle >= 0.0) sampled_threads.store(threads_between(last_sample, sample));
  last_sample = sample;
#endif
}

}  // namespace progsim
