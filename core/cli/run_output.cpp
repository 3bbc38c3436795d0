#include "cli/run_output.hpp"

#include <csignal>
#include <iomanip>
#include <sstream>

#include "common/error.hpp"
#include "contact/contact_potential.hpp"
#include "mesh/mesh_io.hpp"

namespace fs = std::filesystem;

namespace progsim::cli {
namespace {

/// Set by SIGINT during a run.
volatile std::sig_atomic_t g_interrupted = 0;

void on_interrupt(int) {
  g_interrupted = 1;
}

}  // namespace

std::string numbered(const fs::path& dir, const char* stem, int number) {
  std::ostringstream name;
  name << stem << std::setw(5) << std::setfill('0') << number << ".obj";
  return (dir / name.str()).string();
}

std::ofstream open_log(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream log(dir / "steps.jsonl");
  if (!log) fail(Status::io_error, "cannot write " + (dir / "steps.jsonl").string());
  return log;
}

TriangleMesh met_obstacles(const LevelSimulation& sim) {
  const ContactPotential* contact = sim.contact();
  if (!contact || contact->mesh().num_obstacle_vertices == 0) return {};
  const CollisionMesh& mesh = contact->mesh();
  const Faces faces = (mesh.faces.bottomRows(mesh.faces.rows() - mesh.num_shell_faces).array() -
                       mesh.num_shell_vertices)
                          .matrix();
  return {contact->obstacle_positions(), faces};
}

void write_nonempty(const std::string& path, const TriangleMesh& mesh) {
  if (mesh.num_vertices() > 0) write_mesh(path, mesh);
}

void catch_interrupt() {
  std::signal(SIGINT, on_interrupt);
}

bool interrupted() {
  return g_interrupted != 0;
}

void stop_if_interrupted() {
  if (interrupted()) fail(Status::cancelled, "interrupted (SIGINT)");
}

}  // namespace progsim::cli
