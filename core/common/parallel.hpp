#pragma once
/// @file When a loop is worth an OpenMP team, how large a team it gets, and sums whose bits do
/// not depend on that size.
#include <algorithm>
#include <array>

#include "common/thread_budget.hpp"

namespace progsim {

/// Loops over fewer items than this run on the calling thread: forking a team costs more
/// than the work, and on a loaded machine idle team threads steal the cores the work needs
/// (measured: a 441-vertex cloth took 18.5 s for 50 steps with 2-thread regions under load,
/// 1.7 s single-threaded).
constexpr long kMinParallelItems = 2048;

/// The team size of a parallel loop over `items` (the num_threads clause of every progsim
/// loop): 1 below `min_items`, else the thread budget (thread_budget.hpp).
inline int loop_threads(long items, long min_items = kMinParallelItems) {
  return items < min_items ? 1 : thread_budget();
}

/// Σ_{i<n} term(i), the same bits on any number of threads (the automatic thread budget follows
/// the machine's load, and a run's result must not): the items are cut into blocks fixed by n
/// alone (at least kMinParallelItems items, at most 256 blocks), the blocks are summed in
/// parallel and their sums added in order. Below 2 kMinParallelItems it is the plain
/// left-to-right sum. Allocation-free.
template <class Term>
double ordered_sum(long n, Term term) {
  constexpr long kMaxBlocks = 256;
  const long block = std::max(kMinParallelItems, (n + kMaxBlocks - 1) / kMaxBlocks);
  const int blocks = static_cast<int>((n + block - 1) / block);
  std::array<double, kMaxBlocks> partial;
#pragma omp parallel for schedule(static) num_threads(blocks > 1 ? thread_budget() : 1)
  for (int b = 0; b < blocks; ++b) {
    double sum = 0.0;
    for (long i = b * block, end = std::min(n, (b + 1) * block); i < end; ++i) sum += term(i);
    partial[b] = sum;
  }
  double total = 0.0;
  for (int b = 0; b < blocks; ++b) total += partial[b];
  return total;
}

}  // namespace progsim
