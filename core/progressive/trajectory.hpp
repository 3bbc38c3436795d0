#pragma once
/// @file One level's trajectory of a progressive animation (PD Alg. 1: the row x_l^0 … x_l^N of
/// the solution grid), streamed to disk so that memory does not grow with the steps.
#include <cstdio>
#include <memory>

#include "common/types.hpp"

namespace progsim {

/// Frames (positions and velocities of every vertex) appended in time order to an anonymous
/// temporary file, removed when the trajectory is destroyed; any frame can be read back.
/// Memory is O(1) in the number of frames.
class Trajectory {
 public:
  /// An empty trajectory of level `level` (named in error messages), which has `num_vertices`
  /// vertices. Throws Error(io_error) if no temporary file can be made.
  Trajectory(int level, int num_vertices);
  Trajectory(Trajectory&&) noexcept = default;
  Trajectory& operator=(Trajectory&&) noexcept = default;

  /// Appends frame num_frames(): positions and velocities (3|V| each). Throws
  /// Error(invalid_argument) on a wrong size, Error(io_error) if the disk refuses the write
  /// (the frame is then not counted).
  void append(const Vector& positions, const Vector& velocities);
  /// Reads frame `frame` into positions and velocities (resized to 3|V|). Throws
  /// Error(out_of_range) for a frame not written (naming the level, the frame and the level's
  /// number of frames), Error(io_error) on a failed read.
  void read(int frame, Vector& positions, Vector& velocities) const;

  int num_frames() const { return frames_; }
  int num_vertices() const { return vertices_; }

 private:
  struct Close {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::unique_ptr<std::FILE, Close> file_;
  int level_ = 0;
  int vertices_ = 0;
  int frames_ = 0;
};

}  // namespace progsim
