#include "common/error.hpp"

namespace progsim {

const char* status_name(Status status) {
  switch (status) {
    case Status::ok:
      return "ok";
    case Status::invalid_argument:
      return "invalid_argument";
    case Status::invalid_mesh:
      return "invalid_mesh";
    case Status::invalid_scene:
      return "invalid_scene";
    case Status::io_error:
      return "io_error";
    case Status::numerical_failure:
      return "numerical_failure";
    case Status::wrong_call_order:
      return "wrong_call_order";
    case Status::out_of_range:
      return "out_of_range";
    case Status::cancelled:
      return "cancelled";
    case Status::intersecting:
      return "intersecting";
    case Status::internal:
      return "internal";
    case Status::unsupported:
      return "unsupported";
  }
  return "unknown";
}

Error::Error(Status status, const std::string& message)
    : std::runtime_error(message), status_(status) {}

void fail(Status status, const std::string& message) {
  throw Error(status, message);
}

void check_level_exists(int level, int finest) {
  if (level < 0 || level > finest)
    fail(Status::out_of_range, "level " + std::to_string(level) + " does not exist (levels 0 to " +
                                   std::to_string(finest) + ")");
}

}  // namespace progsim
