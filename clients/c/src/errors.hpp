// How a C entry point reports failure: a robotd_status, and a message kept per thread for
// robotd_last_error(). Inside the library a failure is a CallFailure exception; guarded() turns
// it, and any other exception, into the status, so no exception ever reaches C.
#pragma once

#include <exception>
#include <new>
#include <string>
#include <utility>

#include "robotd/result.hpp"
#include "robotd/robotd.h"

namespace robotd::c {

class CallFailure : public std::exception {
 public:
  CallFailure(robotd_status status, std::string message) : status_(status), message_(std::move(message)) {}
  robotd_status status() const { return status_; }
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  robotd_status status_;
  std::string message_;
};

[[noreturn]] void fail(robotd_status status, std::string message);
/// The C++ client's error as the matching status.
[[noreturn]] void fail(const Error& error);

/// The value of a C++ client call, or its error thrown as a CallFailure.
template <class T>
T take(Result<T>&& result) {
  if (!result) fail(result.error());
  return std::move(result).value();
}
inline void check(const Result<void>& result) {
  if (!result) fail(result.error());
}

/// Records the outcome of a call for robotd_last_error(); `function` prefixes a failure's message.
robotd_status record_success() noexcept;
robotd_status record_failure(const char* function, robotd_status status, const char* message) noexcept;

/// Runs `body`, the work of the C entry point `function`, and returns its status.
template <class Body>
robotd_status guarded(const char* function, Body&& body) noexcept {
  try {
    body();
    return record_success();
  } catch (const CallFailure& failure) {
    return record_failure(function, failure.status(), failure.what());
  } catch (const std::bad_alloc&) {
    return record_failure(function, ROBOTD_INTERNAL_ERROR, "out of memory");
  } catch (const std::exception& error) {
    return record_failure(function, ROBOTD_INTERNAL_ERROR, error.what());
  } catch (...) {
    return record_failure(function, ROBOTD_INTERNAL_ERROR, "an unknown exception");
  }
}

}  // namespace robotd::c
