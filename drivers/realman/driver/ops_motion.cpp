// Planned moves, stops, enable and error clearing.
#include <chrono>
#include <cstdio>
#include <thread>

#include "driver/realman_ops.hpp"

namespace robotd::realman {
namespace {

std::string format_rad(double value) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.4g", value);
  return text.data();
}

PlannedMove read_planned_move(OpArguments& arguments) {
  PlannedMove move;
  JsonReader& reader = arguments.reader();
  move.speed_percent = static_cast<int>(reader.integer_or("v", move.speed_percent, 1, 100));
  move.blend_percent = static_cast<int>(reader.integer_or("r", move.blend_percent, 0, 100));
  move.trajectory_connect = reader.boolean_or("trajectory_connect", move.trajectory_connect);
  return move;
}

/// A connected segment waits for the next move to start, so there is nothing to wait for.
std::optional<Error> check_block(std::string_view op, const PlannedMove& move, bool block) {
  if (!(block && move.trajectory_connect)) return std::nullopt;
  return make_error(ErrorCode::kInvalidArgument,
                    std::string(op) +
                        ": block needs trajectory_connect false (a connected segment only starts with "
                        "the next move); pass \"block\": false");
}

}  // namespace

std::optional<Error> RealmanOps::check_can_move(std::string_view op) const {
  // A session that ended on the way left a slow stop decelerating the arm; a move sent now would
  // be cut short by it.
  constexpr auto kStopWait = std::chrono::seconds(2);
  const auto deadline = std::chrono::steady_clock::now() + kStopWait;
  while (driver_.link_.stopping() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (driver_.link_.stopping()) {
    return make_error(ErrorCode::kRefused, std::string(op) + ": the arm is still slowing down after its session ended");
  }
  if (driver_.session_streaming_.load(std::memory_order_relaxed)) {
    return make_error(ErrorCode::kRefused,
                      std::string(op) + ": a session is streaming joint commands to this arm; release it first");
  }
  if (const ArmFeedback feedback = driver_.link_.feedback(); feedback.fault.code != 0) {
    return make_error(ErrorCode::kRefused,
                      std::string(op) + ": " + feedback.fault.text.data() + "; clear it first (robotctl recover)");
  }
  return std::nullopt;
}

Result<nlohmann::json> RealmanOps::movej(const nlohmann::json& args) {
  OpArguments arguments("movej", args);
  JsonReader& reader = arguments.reader();
  const std::size_t dof = driver_.params_.model.dof;
  reader.require("joints_rad", "an array of " + std::to_string(dof) + " joint angles (rad)");
  const auto joints = reader.number_array("joints_rad");
  const PlannedMove move = read_planned_move(arguments);
  const bool block = arguments.block();
  const double timeout_s = arguments.timeout_s();
  if (joints && joints->size() != dof) {
    reader.error("joints_rad", "expected " + std::to_string(dof) + " angles, got " + std::to_string(joints->size()));
  } else if (joints) {
    for (std::size_t j = 0; j < dof; ++j) {
      const driver::JointLimits& limits = driver_.params_.limits[j];
      if ((*joints)[j] < limits.position_min_rad || (*joints)[j] > limits.position_max_rad) {
        reader.error("joints_rad", "joint" + std::to_string(j + 1) + " = " + format_rad((*joints)[j]) +
                                       " rad is outside its range " + format_rad(limits.position_min_rad) + " .. " +
                                       format_rad(limits.position_max_rad) + " rad");
      }
    }
  }
  if (auto error = arguments.finish()) return *error;
  if (auto error = check_block("movej", move, block)) return *error;
  if (auto error = check_can_move("movej")) return *error;
  return send(movej_request(*joints, move), block ? std::optional(Device::kArm) : std::nullopt, timeout_s);
}

Result<nlohmann::json> RealmanOps::cartesian_move(const std::string& op, const nlohmann::json& args) {
  OpArguments arguments(op, args);
  JsonReader& reader = arguments.reader();
  EulerPose pose;
  const NumberRange reach{.min = -2.0, .max = 2.0};
  const NumberRange angle{.min = -7.0, .max = 7.0};
  const std::array<const char*, 3> position_keys{"x_m", "y_m", "z_m"};
  const std::array<const char*, 3> euler_keys{"rx_rad", "ry_rad", "rz_rad"};
  for (std::size_t i = 0; i < 3; ++i) {
    reader.require(position_keys[i], "a number (m)");
    reader.require(euler_keys[i], "a number (rad)");
    pose.position_m[i] = reader.number(position_keys[i], reach).value_or(0);
    pose.euler_rad[i] = reader.number(euler_keys[i], angle).value_or(0);
  }
  const PlannedMove move = read_planned_move(arguments);
  const bool block = arguments.block();
  const double timeout_s = arguments.timeout_s();
  if (auto error = arguments.finish()) return *error;
  if (auto error = check_block(op, move, block)) return *error;
  if (auto error = check_can_move(op)) return *error;
  const nlohmann::json message = op == "movel" ? movel_request(pose, move) : movej_p_request(pose, move);
  return send(message, block ? std::optional(Device::kArm) : std::nullopt, timeout_s);
}

Result<nlohmann::json> RealmanOps::plain(const std::string& op, const nlohmann::json& args) {
  OpArguments arguments(op, args);
  if (auto error = arguments.finish()) return *error;
  return send(plain_request(op), std::nullopt, 0);
}

Result<nlohmann::json> RealmanOps::set_joint_en_state(const nlohmann::json& args) {
  OpArguments arguments("set_joint_en_state", args);
  JsonReader& reader = arguments.reader();
  reader.require("joint", "the joint number, 1.." + std::to_string(driver_.params_.model.dof));
  reader.require("enable", "true or false");
  const auto joint = reader.integer("joint", 1, static_cast<std::int64_t>(driver_.params_.model.dof));
  const bool enable = reader.boolean_or("enable", true);
  if (auto error = arguments.finish()) return *error;
  return send(set_joint_en_state_request(static_cast<int>(*joint), enable), std::nullopt, 0);
}

Result<nlohmann::json> RealmanOps::set_joint_clear_err(const nlohmann::json& args) {
  OpArguments arguments("set_joint_clear_err", args);
  JsonReader& reader = arguments.reader();
  reader.require("joint", "the joint number, 1.." + std::to_string(driver_.params_.model.dof));
  const auto joint = reader.integer("joint", 1, static_cast<std::int64_t>(driver_.params_.model.dof));
  if (auto error = arguments.finish()) return *error;
  return send(set_joint_clear_err_request(static_cast<int>(*joint)), std::nullopt, 0);
}

Result<nlohmann::json> RealmanOps::set_arm_power(const nlohmann::json& args) {
  OpArguments arguments("set_arm_power", args);
  JsonReader& reader = arguments.reader();
  reader.require("on", "true or false");
  const bool on = reader.boolean_or("on", true);
  if (auto error = arguments.finish()) return *error;
  return send(set_arm_power_request(on), std::nullopt, 0);
}

}  // namespace robotd::realman
