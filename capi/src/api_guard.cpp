#include "api_guard.hpp"

namespace progsim::capi {
namespace {
thread_local std::string thread_error;
}  // namespace

void api_fail(ps_status status, const std::string& message) {
  throw ApiError(status, message);
}

void require(const void* pointer, const char* what) {
  if (!pointer) api_fail(PS_ERROR_NULL_ARGUMENT, std::string(what) + " is NULL");
}

ps_status to_ps_status(Status status) {
  switch (status) {
    case Status::ok:
      return PS_OK;
    case Status::invalid_argument:
      return PS_ERROR_INVALID_ARGUMENT;
    case Status::invalid_mesh:
      return PS_ERROR_INVALID_MESH;
    case Status::invalid_scene:
      return PS_ERROR_INVALID_SCENE;
    case Status::io_error:
      return PS_ERROR_IO;
    case Status::numerical_failure:
      return PS_ERROR_NUMERICAL;
    case Status::wrong_call_order:
      return PS_ERROR_WRONG_CALL_ORDER;
    case Status::out_of_range:
      return PS_ERROR_OUT_OF_RANGE;
    case Status::cancelled:
      return PS_ERROR_CANCELLED;
    case Status::intersecting:
      return PS_ERROR_INTERSECTING;
    case Status::internal:
      return PS_ERROR_INTERNAL;
    case Status::unsupported:
      return PS_ERROR_UNSUPPORTED;
  }
  return PS_ERROR_INTERNAL;
}

void set_thread_error(const std::string& message) {
  thread_error = message;
}

}  // namespace progsim::capi

extern "C" PS_API const char* ps_last_error(void) {
  return progsim::capi::thread_error.c_str();
}
