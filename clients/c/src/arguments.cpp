#include "arguments.hpp"

#include <cstring>

namespace robotd::c {

std::string text_argument(const char* text, std::string_view name, std::size_t capacity) {
  if (text == nullptr) return {};
  const std::size_t length = std::strlen(text);
  if (length >= capacity) {
    fail(ROBOTD_INVALID_ARGUMENT, std::string(name) + " is " + std::to_string(length) +
                                      " bytes long: expected at most " + std::to_string(capacity - 1));
  }
  return {text, length};
}

void require_joint_count(std::size_t count, std::string_view name) {
  if (count > ROBOTD_MAX_JOINTS) {
    fail(ROBOTD_INVALID_ARGUMENT, std::string(name) + " is " + std::to_string(count) +
                                      ": expected at most ROBOTD_MAX_JOINTS (" + std::to_string(ROBOTD_MAX_JOINTS) +
                                      ")");
  }
}

ControlMode mode_argument(robotd_control_mode mode, std::string_view name) {
  const auto converted = static_cast<ControlMode>(mode);
  if (!is_valid(converted)) {
    fail(ROBOTD_INVALID_ARGUMENT, std::string(name) + " is " + std::to_string(static_cast<int>(mode)) +
                                      ": expected ROBOTD_MODE_POSITION, ROBOTD_MODE_TORQUE or ROBOTD_MODE_MIXED");
  }
  return converted;
}

Behavior behavior_argument(robotd_behavior behavior, std::string_view name) {
  const auto converted = static_cast<Behavior>(behavior);
  if (!is_valid(converted)) {
    fail(ROBOTD_INVALID_ARGUMENT,
         std::string(name) + " is " + std::to_string(static_cast<int>(behavior)) +
             ": expected ROBOTD_BEHAVIOR_KEEP, ROBOTD_BEHAVIOR_DAMPING or ROBOTD_BEHAVIOR_ZERO_TORQUE");
  }
  return converted;
}

LowRateAction low_rate_action_argument(robotd_low_rate_action action, std::string_view name) {
  const auto converted = static_cast<LowRateAction>(action);
  if (!is_valid(converted)) {
    fail(ROBOTD_INVALID_ARGUMENT, std::string(name) + " is " + std::to_string(static_cast<int>(action)) +
                                      ": expected ROBOTD_LOW_RATE_WARN or ROBOTD_LOW_RATE_FALLBACK");
  }
  return converted;
}

Command to_command(const robotd_command& command, std::size_t session_motors) {
  require_joint_count(command.count, "command->count");
  // With no motor ids the values address the session's motors, one each.
  std::size_t values = session_motors;
  Command converted;
  if (command.count > 0) {
    require(command.motor_ids, "command->motor_ids",
            "command->count motor ids (or NULL with count 0 for the session's motors)");
    converted.motor_ids = array_argument(command.motor_ids, command.count);
    values = command.count;
  }
  converted.positions = array_argument(command.positions, values);
  converted.velocities = array_argument(command.velocities, values);
  converted.kp = array_argument(command.kp, values);
  converted.kd = array_argument(command.kd, values);
  converted.torques = array_argument(command.torques, values);
  return converted;
}

std::chrono::milliseconds timeout_argument(std::int32_t timeout_ms, std::string_view name, bool allow_zero) {
  if (timeout_ms < 0 || (timeout_ms == 0 && !allow_zero)) {
    fail(ROBOTD_INVALID_ARGUMENT, std::string(name) + " is " + std::to_string(timeout_ms) + ": expected " +
                                      (allow_zero ? "0 or more" : "more than 0") + " milliseconds");
  }
  return std::chrono::milliseconds(timeout_ms);
}

}  // namespace robotd::c
