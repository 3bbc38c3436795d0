#pragma once
/// @file The exception boundary of the C ABI: every ps_* call runs its body through
/// guarded(), which turns every C++ exception into a status code and a stored message.
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "progsim.h"

namespace progsim::capi {

/// A failure detected by the C layer itself (NULL pointer, small buffer, version...).
class ApiError : public std::runtime_error {
 public:
  ApiError(ps_status status, const std::string& message)
      : std::runtime_error(message), status_(status) {}
  ps_status status() const { return status_; }

 private:
  ps_status status_;
};

/// Throws ApiError(status, message).
[[noreturn]] void api_fail(ps_status status, const std::string& message);

/// Throws ApiError(PS_ERROR_NULL_ARGUMENT) naming `what` if pointer is NULL.
void require(const void* pointer, const char* what);

/// Throws ApiError(PS_ERROR_UNINITIALIZED_DEF) unless `cookie` is `expected`, i.e. the def-struct
/// `def_type` was filled by its `def_type`_init().
void require_initialized(int32_t cookie, int32_t expected, const char* def_type);

/// A def's borrowed array of `count` int32 entries at `values` (nullable when count is 0),
/// copied. A count outside 0 to `max_count` is PS_ERROR_INVALID_ARGUMENT naming `count_name`;
/// NULL values with a positive count is PS_ERROR_NULL_ARGUMENT naming `values_name`.
std::vector<int32_t> borrowed_array(const int32_t* values, int32_t count, const char* values_name,
                                    const char* count_name, int32_t max_count);

/// The ps_status mirroring a core Status.
ps_status to_ps_status(Status status);

/// Stores message as the calling thread's last error (ps_last_error()).
void set_thread_error(const std::string& message);

/// Runs body(); returns PS_OK, or the failure's status after storing its message in
/// *handle_error (nullable: then in the thread's last error). Never throws.
template <typename Body>
int32_t guarded(std::string* handle_error, const char* function, Body&& body) noexcept {
  ps_status status = PS_OK;
  std::string message;
  try {
    body();
  } catch (const ApiError& e) {
    status = e.status();
    message = e.what();
  } catch (const Error& e) {
    status = to_ps_status(e.status());
    message = e.what();
  } catch (const std::bad_alloc&) {
    status = PS_ERROR_OUT_OF_MEMORY;
    message = "out of memory";
  } catch (const std::exception& e) {
    status = PS_ERROR_INTERNAL;
    message = std::string("internal error: ") + e.what();
  } catch (...) {
    status = PS_ERROR_INTERNAL;
    message = "internal error: unknown exception";
  }
  try {
    if (status != PS_OK) message = std::string(function) + ": " + message;
    if (handle_error)
      *handle_error = message;
    else if (status != PS_OK)
      set_thread_error(message);
  } catch (...) {  // storing the message itself ran out of memory: keep the status
  }
  return status;
}

}  // namespace progsim::capi
