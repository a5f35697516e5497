// Checks of what a C caller passes in, each failing with ROBOTD_INVALID_ARGUMENT and a message
// that names the argument, what it was and what is expected.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "errors.hpp"
#include "robotd/client/session.hpp"
#include "robotd/messages.hpp"
#include "robotd/robotd.h"

namespace robotd::c {

/// *pointer; `name` is the argument, `expected` what it should point at.
template <class T>
T& require(T* pointer, std::string_view name, std::string_view expected) {
  if (pointer == nullptr) {
    fail(ROBOTD_INVALID_ARGUMENT, std::string(name) + " is NULL: expected " + std::string(expected));
  }
  return *pointer;
}

/// A text argument where NULL means "".
inline std::string optional_text(const char* text) { return text == nullptr ? std::string() : std::string(text); }

/// The same, at most `capacity` - 1 bytes, so it fits the C structs'
/// fields of that capacity (e.g. a device name in robotd_device_info).
std::string text_argument(const char* text, std::string_view name, std::size_t capacity);

/// An array length: at most ROBOTD_MAX_JOINTS.
void require_joint_count(std::size_t count, std::string_view name);

/// `count` values, or none when `values` is NULL.
template <class T>
std::vector<T> array_argument(const T* values, std::size_t count) {
  if (values == nullptr) return {};
  const std::span<const T> view(values, count);
  return {view.begin(), view.end()};
}

ControlMode mode_argument(robotd_control_mode mode, std::string_view name);
Behavior behavior_argument(robotd_behavior behavior, std::string_view name);
LowRateAction low_rate_action_argument(robotd_low_rate_action action, std::string_view name);
/// A robotd_command for a session of `session_motors` motors.
Command to_command(const robotd_command& command, std::size_t session_motors);
/// A timeout in ms: >= 0, or > 0 when `allow_zero` is false.
std::chrono::milliseconds timeout_argument(std::int32_t timeout_ms, std::string_view name, bool allow_zero);

}  // namespace robotd::c
