/* The checks the C ABI tests count their failures with (one `failures` per test program). */
#ifndef PROGSIM_TESTS_CAPI_CHECK_H
#define PROGSIM_TESTS_CAPI_CHECK_H

#include <stdio.h>
#include <string.h>

#include "progsim.h"

static int failures = 0;

#define CHECK(cond)                                                            \
  do {                                                                         \
    if (!(cond)) {                                                             \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                              \
    }                                                                          \
  } while (0)

/* status == expected and the message contains `needle`. */
#define CHECK_ERROR(status, expected, message, needle)                                        \
  do {                                                                                        \
    const int32_t s_ = (status);                                                              \
    const char* m_ = (message);                                                               \
    if (s_ != (expected) || !strstr(m_, (needle))) {                                          \
      fprintf(stderr, "%s:%d: expected %s with \"%s\", got %s: \"%s\"\n", __FILE__, __LINE__, \
              ps_status_name(expected), (needle), ps_status_name(s_), m_);                    \
      ++failures;                                                                             \
    }                                                                                         \
  } while (0)

#endif
