#pragma once
/// @file `progsim sweep`: design sweeps run by the Python package on Dask (progsim.sweep).
#include <CLI/CLI.hpp>

namespace progsim::cli {

/// Registers `progsim sweep ARGS...`; every argument after `sweep` is handed on unparsed.
CLI::App* add_sweep_command(CLI::App& app);

/// Replaces this process with `$PROGSIM_PYTHON -m progsim sweep ARGS...` (default python3),
/// the one implementation of sweeps (Dask is a Python library). Returns only when the
/// interpreter cannot be started: exit status 2, with the reason on stderr.
int run_sweep_command(const CLI::App& sweep);

}  // namespace progsim::cli
