#pragma once
/// @file Error reporting: every failure is a progsim::Error carrying a status code and a
/// message that names the problem. The C ABI maps the code to its status enum.
#include <stdexcept>
#include <string>

namespace progsim {

/// What kind of failure happened. Values are stable: the C ABI mirrors them.
enum class Status : int {
  ok = 0,
  invalid_argument = 1,   ///< a parameter is out of range or nonsense
  invalid_mesh = 2,       ///< a mesh fails validation (names the first offending element)
  invalid_scene = 3,      ///< a scene description is malformed
  io_error = 4,           ///< a file cannot be read or written
  numerical_failure = 5,  ///< the solver produced non-finite values or could not factorize
  wrong_call_order = 6,   ///< an operation was requested before its prerequisites
  out_of_range = 7,       ///< an index or level does not exist
  cancelled = 8,          ///< a progress callback asked to stop
  intersecting = 9,       ///< a configuration intersects itself or another body
  internal = 10,          ///< a bug in progsim; please report it
  unsupported = 16,       ///< a valid request this version cannot do yet (same value as the C ABI)
};

/// Short stable name of a status ("invalid_mesh", ...).
const char* status_name(Status status);

/// The exception type of progsim. Never crosses the C ABI.
class Error : public std::runtime_error {
 public:
  Error(Status status, const std::string& message);
  Status status() const { return status_; }

 private:
  Status status_;
};

/// Throws Error(status, message).
[[noreturn]] void fail(Status status, const std::string& message);

/// Throws Error(out_of_range) "level L does not exist (levels 0 to F)" unless 0 ≤ level ≤ finest.
void check_level_exists(int level, int finest);

}  // namespace progsim
