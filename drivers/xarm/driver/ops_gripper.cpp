// The xArm gripper: Modbus requests to device 8 on the tool's RS-485 bus, carried by register 124
// (UFACTORY xArm Gripper user manual §3.4.3; the SDK's set_gripper_* calls send the same frames).
// Positions are the gripper's pulses (0 closed, 850 open), speeds its r/min, as in the vendor API.
#include <array>
#include <chrono>
#include <cmath>
#include <thread>

#include "driver/xarm_ops.hpp"

namespace robotd::xarm {
namespace {

constexpr auto kGripperPoll = std::chrono::milliseconds(50);
/// Polls with the position unchanged after which a move has stopped on an object.
constexpr int kStalledPolls = 5;
constexpr int kTargetTolerancePulses = 1;
constexpr double kDefaultGripperTimeoutS = 10;
constexpr std::size_t kGripperBaudIndex = 11;  // kToolBaudRates[11]: 2 Mbit/s

std::uint16_t address(GripperRegister reg) { return static_cast<std::uint16_t>(reg); }

std::int32_t position_of(const std::vector<std::uint16_t>& words) {
  return static_cast<std::int32_t>((static_cast<std::uint32_t>(words[0]) << 16) | words[1]);
}

std::string_view gripper_status_text(int status) {
  switch (status) {
    case kGripperStopped:
      return "stopped";
    case kGripperMoving:
      return "moving";
    case kGripperGripping:
      return "gripping an object";
    default:
      return "status 3 (not defined)";
  }
}

std::string gripper_error_text(int code) {
  return "gripper error " + std::to_string(code) + ": " + servo_error_text(code);
}

}  // namespace

std::optional<Error> XarmOps::check_tool_baud_rate(std::string_view op) {
  auto reply = exchange(op, tool_register_read_request(kToolHostId, kToolBaudRateAddress));
  if (!reply) return reply.error();
  auto index = parse_tool_register_value(reply.value().data);
  if (!index) return make_error(ErrorCode::kTransport, std::string(op) + ": " + index.error().message);
  if (static_cast<std::size_t>(index.value()) == kGripperBaudIndex) return std::nullopt;
  const std::string rate = index.value() >= 0 && static_cast<std::size_t>(index.value()) < kToolBaudRates.size()
                               ? std::to_string(kToolBaudRates[static_cast<std::size_t>(index.value())]) + " baud"
                               : "baud-rate index " + std::to_string(index.value());
  return make_error(ErrorCode::kRefused, std::string(op) + ": the tool's RS-485 bus runs at " + rate +
                                             "; the xArm gripper talks at 2000000 (set it in UFACTORY Studio)");
}

Result<std::vector<std::uint16_t>> XarmOps::gripper_read(std::string_view op, GripperRegister reg,
                                                         std::uint16_t count) {
  auto reply = exchange(op, tool_modbus_read_request(kGripperId, address(reg), count));
  if (!reply) return reply.error();
  auto values = parse_tool_modbus_read_reply(reply.value().data, kGripperId, count);
  if (!values) return make_error(ErrorCode::kTransport, std::string(op) + ": " + values.error().message);
  return values;
}

Result<nlohmann::json> XarmOps::gripper_write(std::string_view op, GripperRegister reg,
                                              std::span<const std::uint16_t> values) {
  const auto count = static_cast<std::uint16_t>(values.size());
  auto reply = exchange(op, tool_modbus_write_request(kGripperId, address(reg), values));
  if (!reply) return reply.error();
  if (auto echoed = parse_tool_modbus_write_reply(reply.value().data, kGripperId, address(reg), count); !echoed) {
    return make_error(ErrorCode::kRefused, std::string(op) + ": " + echoed.error().message);
  }
  auto error = gripper_read(op, GripperRegister::kErrorCode, 1);
  if (!error) return error.error();
  if (error.value()[0] != 0) {
    return make_error(ErrorCode::kRefused, std::string(op) + ": " + gripper_error_text(error.value()[0]) +
                                               " (gripper_clean_error, then gripper_enable)");
  }
  return execution_of(reply.value());
}

Result<nlohmann::json> XarmOps::gripper_enable(const nlohmann::json& args) {
  driver::OpArguments arguments("gripper_enable", args, op_usage("gripper_enable"));
  arguments.reader().require("enable", "true or false");
  const bool enable = arguments.reader().boolean_or("enable", true);
  if (auto error = arguments.finish()) return *error;
  if (auto refused = check_connected("gripper_enable")) return *refused;
  if (auto refused = check_tool_baud_rate("gripper_enable")) return *refused;
  const std::array<std::uint16_t, 1> position_mode{0};
  if (enable) {
    if (auto mode = gripper_write("gripper_enable", GripperRegister::kMode, position_mode); !mode) return mode;
  }
  const std::array<std::uint16_t, 1> value{enable ? std::uint16_t{1} : std::uint16_t{0}};
  return gripper_write("gripper_enable", GripperRegister::kEnable, value);
}

Result<nlohmann::json> XarmOps::gripper_set_speed(const nlohmann::json& args) {
  driver::OpArguments arguments("gripper_set_speed", args, op_usage("gripper_set_speed"));
  arguments.reader().require("speed_rpm", "1 … 5000");
  const auto speed = arguments.reader().integer("speed_rpm", 1, kGripperMaxSpeedRpm);
  if (auto error = arguments.finish()) return *error;
  const std::array<std::uint16_t, 1> value{static_cast<std::uint16_t>(*speed)};
  return gripper_write("gripper_set_speed", GripperRegister::kSpeed, value);
}

Result<nlohmann::json> XarmOps::gripper_move(const std::string& op, const nlohmann::json& args) {
  driver::OpArguments arguments(op, args, op_usage(op));
  JsonReader& reader = arguments.reader();
  std::optional<std::int64_t> target = op == "gripper_open" ? kGripperMaxPulses : 0;
  if (op == "gripper_set_position") {
    reader.require("position", "-10 … 850 pulses (0 closed, 850 open)");
    target = reader.integer("position", kGripperMinPulses, kGripperMaxPulses);
  }
  const std::optional<std::int64_t> speed =
      reader.has("speed_rpm") ? reader.integer("speed_rpm", 1, kGripperMaxSpeedRpm) : std::nullopt;
  const bool wait = reader.boolean_or("wait", false);
  const double timeout_s = reader.number_or("timeout_s", kDefaultGripperTimeoutS, NumberRange{.min = 0.1, .max = 3600});
  if (auto error = arguments.finish()) return *error;
  // A disabled gripper takes the target and never moves: say so rather than wait.
  auto enabled = gripper_read(op, GripperRegister::kEnable, 1);
  if (!enabled) return enabled.error();
  if (enabled.value()[0] == 0) {
    auto error = gripper_read(op, GripperRegister::kErrorCode, 1);
    if (!error) return error.error();
    return make_error(ErrorCode::kRefused,
                      op + ": the gripper is disabled" +
                          (error.value()[0] != 0 ? ": " + gripper_error_text(error.value()[0]) +
                                                       " (gripper_clean_error, then gripper_enable)"
                                                 : " (gripper_enable first)"));
  }
  if (speed) {
    const std::array<std::uint16_t, 1> value{static_cast<std::uint16_t>(*speed)};
    if (auto set = gripper_write(op, GripperRegister::kSpeed, value); !set) return set;
  }
  const auto pulses = static_cast<std::int32_t>(*target);
  const std::array<std::uint16_t, 2> words{static_cast<std::uint16_t>(static_cast<std::uint32_t>(pulses) >> 16),
                                           static_cast<std::uint16_t>(pulses & 0xFFFF)};
  auto result = gripper_write(op, GripperRegister::kTargetPosition, words);
  if (!result || !wait) return result;
  // Done at the target, or when the position stops changing short of it (an object is gripped).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::optional<std::int32_t> last;
  int unchanged = 0;
  for (;;) {
    auto position = gripper_read(op, GripperRegister::kPosition, 2);
    if (!position) return position.error();
    const std::int32_t now = position_of(position.value());
    unchanged = last && *last == now ? unchanged + 1 : 0;
    last = now;
    if (std::abs(now - pulses) <= kTargetTolerancePulses || unchanged >= kStalledPolls) {
      auto status = gripper_status(op);
      if (!status) return status.error();
      result.value()["position"] = now;
      result.value()["completed"] = true;
      result.value()["object_gripped"] = status.value() == kGripperGripping;
      return result;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      return make_error(ErrorCode::kTimeout, op + ": the gripper is at " + std::to_string(now) + " pulses after " +
                                                 std::to_string(std::lround(timeout_s)) + " s, short of " +
                                                 std::to_string(pulses));
    }
    std::this_thread::sleep_for(kGripperPoll);
  }
}

Result<nlohmann::json> XarmOps::gripper_get_position(const nlohmann::json& args) {
  driver::OpArguments arguments("gripper_get_position", args, op_usage("gripper_get_position"));
  if (auto error = arguments.finish()) return *error;
  auto position = gripper_read("gripper_get_position", GripperRegister::kPosition, 2);
  if (!position) return position.error();
  return nlohmann::json{{"position", position_of(position.value())}};
}

Result<nlohmann::json> XarmOps::gripper_get_error(const nlohmann::json& args) {
  driver::OpArguments arguments("gripper_get_error", args, op_usage("gripper_get_error"));
  if (auto error = arguments.finish()) return *error;
  auto code = gripper_read("gripper_get_error", GripperRegister::kErrorCode, 1);
  if (!code) return code.error();
  const int error = code.value()[0];
  return nlohmann::json{{"error", error}, {"error_text", error == 0 ? "" : gripper_error_text(error)}};
}

Result<int> XarmOps::gripper_status(std::string_view op) {
  auto status = gripper_read(op, GripperRegister::kStatus, 1);
  if (!status) return status.error();
  return static_cast<int>(status.value()[0] & kGripperStatusBits);
}

Result<nlohmann::json> XarmOps::gripper_get_status(const nlohmann::json& args) {
  driver::OpArguments arguments("gripper_get_status", args, op_usage("gripper_get_status"));
  if (auto error = arguments.finish()) return *error;
  auto status = gripper_status("gripper_get_status");
  if (!status) return status.error();
  return nlohmann::json{{"status", status.value()},
                        {"status_text", gripper_status_text(status.value())},
                        {"object_gripped", status.value() == kGripperGripping}};
}

Result<nlohmann::json> XarmOps::gripper_clean_error(const nlohmann::json& args) {
  driver::OpArguments arguments("gripper_clean_error", args, op_usage("gripper_clean_error"));
  if (auto error = arguments.finish()) return *error;
  const std::array<std::uint16_t, 1> value{1};
  return gripper_write("gripper_clean_error", GripperRegister::kResetError, value);
}

}  // namespace robotd::xarm
