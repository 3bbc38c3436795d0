#pragma once
/// @file What `progsim run` writes besides its summary: numbered meshes and the step log, and
/// the SIGINT flag that stops a run at its next step.
#include <filesystem>
#include <fstream>
#include <string>

#include "mesh/triangle_mesh.hpp"
#include "sim/level_simulation.hpp"

namespace progsim::cli {

/// dir/stemNNNNN.obj (five digits).
std::string numbered(const std::filesystem::path& dir, const char* stem, int number);

/// Creates `dir` and opens dir/steps.jsonl. Throws Error(io_error) if it cannot be written.
std::ofstream open_log(const std::filesystem::path& dir);

/// The obstacles as `sim`'s contact meets them now: their positions (a progressive level's
/// coarse copies, where its script rounds left them) and faces; empty without any.
TriangleMesh met_obstacles(const LevelSimulation& sim);

/// Writes `mesh` unless it is empty.
void write_nonempty(const std::string& path, const TriangleMesh& mesh);

/// Installs the SIGINT handler (Ctrl-C): the run stops at its next step, settle or refinement.
void catch_interrupt();
/// Whether SIGINT has arrived.
bool interrupted();
/// Throws Error(cancelled) once SIGINT has arrived.
void stop_if_interrupted();

}  // namespace progsim::cli
