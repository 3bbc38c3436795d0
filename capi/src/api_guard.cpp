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

void require_initialized(int32_t cookie, int32_t expected, const char* def_type) {
  if (cookie != expected)
    api_fail(PS_ERROR_UNINITIALIZED_DEF,
             std::string("the ") + def_type + " was not filled by " + def_type + "_init()");
}

std::vector<int32_t> borrowed_array(const int32_t* values, int32_t count, const char* values_name,
                                    const char* count_name, int32_t max_count) {
  if (count < 0 || count > max_count)
    api_fail(PS_ERROR_INVALID_ARGUMENT, std::string(count_name) + " = " + std::to_string(count) +
                                            " must be in 0 to " + std::to_string(max_count));
  if (count > 0) require(values, values_name);
  return std::vector<int32_t>(values, values + count);
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
