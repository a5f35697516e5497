// Errors cross robotd's boundaries as values: a Result holds either a value or an Error
// with a code a program can branch on and a message a person can act on.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace robotd {

enum class ErrorCode {
  kTimeout,          // no answer within the deadline
  kNotAvailable,     // robotd (or the service) is not reachable on this DDS domain
  kRefused,          // robotd answered and said no; the message says why
  kInvalidArgument,  // the caller passed something malformed; nothing was sent
  kTransport,        // the DDS layer failed
  kNotPermitted,     // DDS Security refused it: this participant's identity or permissions do not allow it
};

const char* to_string(ErrorCode code);

struct Error {
  ErrorCode code = ErrorCode::kTransport;
  std::string message;
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : state_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }
  T& value() & { return std::get<T>(state_); }
  const T& value() const& { return std::get<T>(state_); }
  T&& value() && { return std::get<T>(std::move(state_)); }
  const Error& error() const { return std::get<Error>(state_); }

 private:
  std::variant<T, Error> state_;
};

template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { return error_; }

 private:
  Error error_;
  bool ok_ = true;
};

inline Error make_error(ErrorCode code, std::string message) { return Error{code, std::move(message)}; }

}  // namespace robotd
