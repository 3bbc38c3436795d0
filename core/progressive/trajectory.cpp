#include "progressive/trajectory.hpp"

#include <string>

#include "common/error.hpp"

namespace progsim {

namespace {

/// "level L's trajectory: ", the start of the trajectory's error messages.
std::string about(int level) {
  return "level " + std::to_string(level) + "'s trajectory: ";
}

}  // namespace

Trajectory::Trajectory(int level, int num_vertices)
    : file_(std::tmpfile()), level_(level), vertices_(num_vertices) {
  if (!file_) fail(Status::io_error, about(level_) + "cannot create a temporary file");
}

void Trajectory::append(const Vector& positions, const Vector& velocities) {
  const Eigen::Index n = 3 * Eigen::Index{vertices_};
  if (positions.size() != n || velocities.size() != n)
    fail(Status::invalid_argument, about(level_) + "a frame of " +
                                       std::to_string(positions.size()) + " positions and " +
                                       std::to_string(velocities.size()) +
                                       " velocities, the level has " + std::to_string(n) + " DOFs");
  const long frame_bytes = 2L * n * static_cast<long>(sizeof(double));
  std::FILE* f = file_.get();
  const bool written = std::fseek(f, frames_ * frame_bytes, SEEK_SET) == 0 &&
                       std::fwrite(positions.data(), sizeof(double), n, f) == std::size_t(n) &&
                       std::fwrite(velocities.data(), sizeof(double), n, f) == std::size_t(n);
  if (!written)
    fail(Status::io_error, about(level_) + "writing frame " + std::to_string(frames_) + " failed");
  ++frames_;
}

void Trajectory::read(int frame, Vector& positions, Vector& velocities) const {
  if (frame < 0 || frame >= frames_)
    fail(Status::out_of_range, "frame " + std::to_string(frame) + " of level " +
                                   std::to_string(level_) + " has not been computed (level " +
                                   std::to_string(level_) + " has " + std::to_string(frames_) +
                                   (frames_ == 1 ? " frame)" : " frames)"));
  const Eigen::Index n = 3 * Eigen::Index{vertices_};
  positions.resize(n);
  velocities.resize(n);
  const long frame_bytes = 2L * n * static_cast<long>(sizeof(double));
  std::FILE* f = file_.get();
  const bool read = std::fseek(f, frame * frame_bytes, SEEK_SET) == 0 &&
                    std::fread(positions.data(), sizeof(double), n, f) == std::size_t(n) &&
                    std::fread(velocities.data(), sizeof(double), n, f) == std::size_t(n);
  if (!read)
    fail(Status::io_error, about(level_) + "reading frame " + std::to_string(frame) + " failed");
}

}  // namespace progsim
