/* Assertions for the C API tests: each reports where and what failed (with robotd_last_error()
 * for calls) and returns false from the test case. */
#ifndef ROBOTD_TEST_CHECK_H
#define ROBOTD_TEST_CHECK_H

#include <robotd/robotd.h>
#include <stdio.h>
#include <string.h>

#define CHECK(condition)                                                            \
  do {                                                                              \
    if (!(condition)) {                                                             \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition); \
      return false;                                                                 \
    }                                                                               \
  } while (0)

/* `call` returns `expected`, and robotd_last_error() contains `text` ("" = anything). */
#define CHECK_CALL(expected, call, text)                                                                             \
  do {                                                                                                               \
    const robotd_status status_ = (call);                                                                            \
    if (status_ != (expected) || strstr(robotd_last_error(), (text)) == NULL) {                                      \
      fprintf(stderr, "%s:%d: %s\n  returned %s (expected %s)\n  last error: \"%s\" (expected to contain \"%s\")\n", \
              __FILE__, __LINE__, #call, robotd_status_name(status_), robotd_status_name(expected),                  \
              robotd_last_error(), (text));                                                                          \
      return false;                                                                                                  \
    }                                                                                                                \
  } while (0)

#define CHECK_OK(call) CHECK_CALL(ROBOTD_OK, call, "")

#endif /* ROBOTD_TEST_CHECK_H */
