// The library's own thread count (issue 33 §6): a fixed setting is obeyed and nonsense refused
// with the setting unchanged; the automatic one counts idle and own processor time, and leaves
// out a core that another process keeps busy.
#include <gtest/gtest.h>
#include <omp.h>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include "common/error.hpp"
#include "common/parallel.hpp"
#include "common/thread_budget.hpp"

using namespace progsim;

TEST(ThreadBudget, AFixedCountIsObeyedAndNonsenseIsRefusedUnchanged) {
  set_thread_budget(3);
  EXPECT_EQ(thread_budget_setting(), 3);
  EXPECT_EQ(thread_budget(), 3);
  EXPECT_EQ(loop_threads(kMinParallelItems), 3);
  EXPECT_EQ(loop_threads(kMinParallelItems - 1), 1);  // small loops stay on the caller
  EXPECT_THROW(set_thread_budget(-1), Error);
  EXPECT_THROW(set_thread_budget(1025), Error);
  EXPECT_EQ(thread_budget_setting(), 3);
  set_thread_budget(0);
  EXPECT_EQ(thread_budget_setting(), 0);
  EXPECT_GE(thread_budget(), 1);
  EXPECT_LE(thread_budget(), omp_get_max_threads());
}

TEST(ThreadBudget, FreeProcessorsAreTheIdleOnesPlusThoseThisProcessUsed) {
  EXPECT_EQ(free_processors(1.0, 1.0, 1.0, 2), 2);   // alone: one core idle, one ours
  EXPECT_EQ(free_processors(0.0, 1.0, 1.0, 2), 1);   // another process holds a core
  EXPECT_EQ(free_processors(0.05, 0.9, 1.0, 2), 1);  // ... while our team spins on the other
  EXPECT_EQ(free_processors(0.0, 0.0, 1.0, 2), 1);   // never below one
  EXPECT_EQ(free_processors(7.5, 0.0, 1.0, 4), 4);   // never above the affinity mask
  EXPECT_EQ(free_processors(1.0, 0.0, 0.0, 2), 2);   // no time passed: all allowed
}

TEST(ThreadBudget, AutomaticLeavesOutTheCoresOtherProcessesKeepBusy) {
  cpu_set_t mask;
  ASSERT_EQ(sched_getaffinity(0, sizeof(mask), &mask), 0);
  const int allowed = CPU_COUNT(&mask);
  std::vector<pid_t> spinners;
  for (int k = 0; k + 1 < allowed; ++k) {  // every core but one
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      volatile unsigned long spin = 0;
      for (;;) spin = spin + 1;
    }
    spinners.push_back(pid);
  }
  set_thread_budget(0);
  for (int sample = 0; sample < 3; ++sample) {
    refresh_thread_budget();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  refresh_thread_budget();
  const int chosen = thread_budget();
  for (pid_t pid : spinners) {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
  EXPECT_EQ(chosen, 1) << allowed << " allowed processors, " << spinners.size() << " busy";
}

TEST(OrderedSum, HasTheSameBitsOnOneTwoAndThreeThreads) {
  // 10^5 terms of mixed magnitude: an OpenMP reduction's partial sums differ with the team.
  const auto term = [](long i) { return 1.0 / (1.0 + i) + 1e-3 * std::sin(0.1 * i); };
  const long n = 100000;
  std::vector<double> sums;
  for (int threads : {1, 2, 3}) {
    set_thread_budget(threads);
    sums.push_back(ordered_sum(n, term));
  }
  set_thread_budget(0);
  EXPECT_EQ(sums[0], sums[1]);
  EXPECT_EQ(sums[0], sums[2]);
  double plain = 0.0;  // below 2 kMinParallelItems: the left-to-right sum itself
  for (long i = 0; i < kMinParallelItems; ++i) plain += term(i);
  EXPECT_EQ(ordered_sum(kMinParallelItems, term), plain);
  // Closed forms: the harmonic number H_n ≈ ln n + γ + 1/2n, and Σ_{i<n} sin(ai) =
  // sin(na/2) sin((n − 1)a/2) / sin(a/2).
  const double harmonic = std::log(static_cast<double>(n)) + 0.5772156649015329 + 0.5 / n;
  const double sines = std::sin(0.05 * n) * std::sin(0.05 * (n - 1)) / std::sin(0.05);
  EXPECT_NEAR(sums[0], harmonic + 1e-3 * sines, 1e-9);
}
