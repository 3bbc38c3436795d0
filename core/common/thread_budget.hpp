#pragma once
/// @file How many threads progsim's parallel loops use, chosen by the library itself so that
/// a process embedding it needs no environment variable to stay fast on a shared machine
/// (issue 33 §6). OpenMP's default wait policy lets idle team threads spin; when another
/// process holds one of two cores, those spins take the core the working thread needs
/// (measured: a contact benchmark 5.6x slower than with OMP_WAIT_POLICY=passive). A loop run on
/// one thread wakes no team, so no thread spins.

namespace progsim {

/// Fixes the number of threads of progsim's parallel loops: 1 to 1024, or 0 for automatic (the
/// default). Process-wide; takes effect at the next loop. Throws Error(invalid_argument) on
/// any other value.
void set_thread_budget(int threads);

/// The setting: 0 automatic, else the fixed count.
int thread_budget_setting();

/// The threads a large parallel loop gets now: the fixed count, or (automatic) the processors
/// this process may run on that other processes left idle over the last sampling window,
/// rounded, at least 1 and at most omp_get_max_threads() (so OMP_NUM_THREADS still caps it).
/// Off Linux, automatic is omp_get_max_threads().
int thread_budget();

/// Processors left to this process over a window of `wall_seconds`: those idle
/// (`idle_seconds` summed over the `allowed` processors of its affinity mask) plus those it
/// used itself (`own_cpu_seconds`, spinning included), rounded, from 1 to `allowed`.
int free_processors(double idle_seconds, double own_cpu_seconds, double wall_seconds, int allowed);

/// Samples the machine's load again when the last sample is older than the window (0.25 s):
/// /proc/stat's idle time of the processors in this process's affinity mask, less this
/// process's own CPU time (its spinning threads are not "other" load). Cheap when the window
/// has not passed. Call outside parallel regions: the Newton solver calls it every iteration.
void refresh_thread_budget();

}  // namespace progsim
