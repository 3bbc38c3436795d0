// Version queries and the load-time ABI check (STYLE.md item 7).
#include <string>

#include "api_guard.hpp"

using progsim::capi::api_fail;
using progsim::capi::guarded;

extern "C" {

PS_API int32_t ps_version(void) {
  return PS_VERSION_HEADER;
}

PS_API const char* ps_version_string(void) {
  return PROGSIM_VERSION_STRING;
}

PS_API int32_t ps_check_version(int32_t header_version) {
  return guarded(nullptr, "ps_check_version", [&] {
    const int32_t major = header_version / 10000, minor = header_version / 100 % 100;
    // Before 1.0 a minor version may grow the structs the library fills (ps_level_stats in
    // 0.5): an older caller's buffer would be too small, so the minor must match too.
    const bool compatible = major == PS_VERSION_MAJOR &&
                            (major == 0 ? minor == PS_VERSION_MINOR : minor <= PS_VERSION_MINOR);
    if (header_version < 0 || !compatible)
      api_fail(PS_ERROR_VERSION_MISMATCH, "the caller was built against progsim header version " +
                                              std::to_string(header_version) +
                                              " but the library is " +
                                              std::to_string(PS_VERSION_HEADER) + " (" +
                                              PROGSIM_VERSION_STRING + "); rebuild the caller");
  });
}

PS_API const char* ps_status_name(int32_t status) {
  switch (status) {
#define PS_STATUS_CASE(name) \
  case name:                 \
    return #name;
    PS_STATUS_CASE(PS_OK)
    PS_STATUS_CASE(PS_ERROR_INVALID_ARGUMENT)
    PS_STATUS_CASE(PS_ERROR_INVALID_MESH)
    PS_STATUS_CASE(PS_ERROR_INVALID_SCENE)
    PS_STATUS_CASE(PS_ERROR_IO)
    PS_STATUS_CASE(PS_ERROR_NUMERICAL)
    PS_STATUS_CASE(PS_ERROR_WRONG_CALL_ORDER)
    PS_STATUS_CASE(PS_ERROR_OUT_OF_RANGE)
    PS_STATUS_CASE(PS_ERROR_CANCELLED)
    PS_STATUS_CASE(PS_ERROR_INTERSECTING)
    PS_STATUS_CASE(PS_ERROR_INTERNAL)
    PS_STATUS_CASE(PS_ERROR_NULL_ARGUMENT)
    PS_STATUS_CASE(PS_ERROR_BUFFER_TOO_SMALL)
    PS_STATUS_CASE(PS_ERROR_UNINITIALIZED_DEF)
    PS_STATUS_CASE(PS_ERROR_VERSION_MISMATCH)
    PS_STATUS_CASE(PS_ERROR_OUT_OF_MEMORY)
    PS_STATUS_CASE(PS_ERROR_UNSUPPORTED)
#undef PS_STATUS_CASE
  }
  return "PS_ERROR_UNKNOWN_STATUS";
}

}  // extern "C"
