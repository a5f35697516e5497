#include "errors.hpp"

namespace robotd::c {
namespace {

// The calling thread's message for its last call. When even the message cannot be allocated,
// `fallback` points at a static text instead.
struct LastError {
  std::string text;
  const char* fallback = nullptr;
};
thread_local LastError last_error;

robotd_status status_of(ErrorCode code) {
  switch (code) {
    case ErrorCode::kTimeout:
      return ROBOTD_TIMEOUT;
    case ErrorCode::kNotAvailable:
      return ROBOTD_NOT_AVAILABLE;
    case ErrorCode::kRefused:
      return ROBOTD_REFUSED;
    case ErrorCode::kInvalidArgument:
      return ROBOTD_INVALID_ARGUMENT;
    case ErrorCode::kTransport:
      return ROBOTD_TRANSPORT;
    case ErrorCode::kNotPermitted:
      return ROBOTD_NOT_PERMITTED;
  }
  return ROBOTD_INTERNAL_ERROR;
}

}  // namespace

void fail(robotd_status status, std::string message) { throw CallFailure(status, std::move(message)); }

void fail(const Error& error) { fail(status_of(error.code), error.message); }

robotd_status record_success() noexcept {
  last_error.text.clear();
  last_error.fallback = nullptr;
  return ROBOTD_OK;
}

robotd_status record_failure(const char* function, robotd_status status, const char* message) noexcept {
  try {
    last_error.text = std::string(function) + ": " + message;
    last_error.fallback = nullptr;
  } catch (...) {
    last_error.fallback = "out of memory for the error message";
  }
  return status;
}

}  // namespace robotd::c

extern "C" {

const char* robotd_last_error(void) {
  const auto& error = robotd::c::last_error;
  return error.fallback != nullptr ? error.fallback : error.text.c_str();
}

const char* robotd_status_name(robotd_status status) {
  switch (status) {
    case ROBOTD_OK:
      return "ROBOTD_OK";
    case ROBOTD_TIMEOUT:
      return "ROBOTD_TIMEOUT";
    case ROBOTD_NOT_AVAILABLE:
      return "ROBOTD_NOT_AVAILABLE";
    case ROBOTD_REFUSED:
      return "ROBOTD_REFUSED";
    case ROBOTD_INVALID_ARGUMENT:
      return "ROBOTD_INVALID_ARGUMENT";
    case ROBOTD_TRANSPORT:
      return "ROBOTD_TRANSPORT";
    case ROBOTD_NOT_PERMITTED:
      return "ROBOTD_NOT_PERMITTED";
    case ROBOTD_BUFFER_TOO_SMALL:
      return "ROBOTD_BUFFER_TOO_SMALL";
    case ROBOTD_INTERNAL_ERROR:
      return "ROBOTD_INTERNAL_ERROR";
  }
  return "ROBOTD_UNKNOWN_STATUS";
}

}  // extern "C"
