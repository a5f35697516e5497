// What a planner returns: the plan, or an error that says what was wrong and what would do.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace robotd::motion {

/// Why a move cannot be planned, in words for the user.
struct Error {
  std::string message;
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}      // NOLINT(google-explicit-constructor): a plan is a result
  Result(Error error) : state_(std::move(error)) {}  // NOLINT(google-explicit-constructor): so is its failure

  bool ok() const noexcept { return std::holds_alternative<T>(state_); }
  explicit operator bool() const noexcept { return ok(); }

  /// The plan; only when ok() (std::bad_variant_access otherwise).
  const T& value() const& { return std::get<T>(state_); }
  T& value() & { return std::get<T>(state_); }
  T&& value() && { return std::get<T>(std::move(state_)); }
  const T* operator->() const { return &value(); }

  /// The error; only when !ok() (std::bad_variant_access otherwise).
  const std::string& error() const { return std::get<Error>(state_).message; }

 private:
  std::variant<T, Error> state_;
};

}  // namespace robotd::motion
