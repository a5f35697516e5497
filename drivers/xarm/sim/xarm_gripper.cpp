#include "xarm_gripper.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::xarm::sim {
namespace {

constexpr std::uint8_t kIllegalAddress = 2;
constexpr std::uint8_t kIllegalValue = 3;

constexpr std::uint16_t address_of(GripperRegister reg) { return static_cast<std::uint16_t>(reg); }
constexpr std::uint16_t high_word(std::int32_t value) {
  return static_cast<std::uint16_t>(static_cast<std::uint32_t>(value) >> 16);
}
constexpr std::uint16_t low_word(std::int32_t value) { return static_cast<std::uint16_t>(value & 0xFFFF); }

}  // namespace

void XarmGripper::advance(double dt_s) {
  if (!enabled_ || error_ != 0) return;
  const double step = kPulsesPerSecondPerRpm * speed_rpm_ * dt_s;
  const double stop = stop_position();
  const double to_go = stop - position_;
  position_ = std::abs(to_go) <= step ? stop : position_ + std::copysign(step, to_go);
}

double XarmGripper::stop_position() const {
  const bool closes_onto_object = object_pulses_ > 0 && target_ < object_pulses_ && position_ >= object_pulses_;
  return closes_onto_object ? object_pulses_ : target_;
}

std::optional<std::uint16_t> XarmGripper::read(std::uint16_t address) const {
  const auto position = static_cast<std::int32_t>(std::lround(position_));
  switch (static_cast<GripperRegister>(address)) {
    case GripperRegister::kStatus:
      if (enabled_ && position_ != stop_position()) return kGripperMoving;
      return stop_position() != target_ ? kGripperGripping : kGripperStopped;
    case GripperRegister::kErrorCode:
      return static_cast<std::uint16_t>(error_);
    case GripperRegister::kEnable:
      return enabled_ ? 1 : 0;
    case GripperRegister::kMode:
      return static_cast<std::uint16_t>(mode_);
    case GripperRegister::kResetError:
      return 0;
    case GripperRegister::kSpeed:
      return static_cast<std::uint16_t>(speed_rpm_);
    case GripperRegister::kTargetPosition:
      return high_word(target_);
    case GripperRegister::kPosition:
      return high_word(position);
    case GripperRegister::kVersionMajor:
      return kVersion[0];
  }
  if (address == address_of(GripperRegister::kTargetPosition) + 1) return low_word(target_);
  if (address == address_of(GripperRegister::kPosition) + 1) return low_word(position);
  if (address == address_of(GripperRegister::kVersionMajor) + 1) return kVersion[1];
  if (address == address_of(GripperRegister::kVersionMajor) + 2) return kVersion[2];
  return std::nullopt;
}

bool XarmGripper::write(std::uint16_t address, std::uint16_t value) {
  switch (static_cast<GripperRegister>(address)) {
    case GripperRegister::kEnable:
      if (value > 1) return false;
      enabled_ = value == 1 && error_ == 0;
      return true;
    case GripperRegister::kMode:
      if (value != 0) return false;  // position mode is the only one the xArm gripper has
      mode_ = value;
      return true;
    case GripperRegister::kResetError:
      error_ = 0;
      return true;
    case GripperRegister::kSpeed:
      if (value < 1 || value > kGripperMaxSpeedRpm) return false;
      speed_rpm_ = value;
      return true;
    case GripperRegister::kTargetPosition:
      target_high_ = value;
      return true;
    default:
      break;
  }
  if (address == address_of(GripperRegister::kTargetPosition) + 1) {
    const auto target = static_cast<std::int32_t>((static_cast<std::uint32_t>(target_high_) << 16) | value);
    if (target < kGripperMinPulses || target > kGripperMaxPulses) return false;
    target_ = target;
    return true;
  }
  return false;
}

Bytes XarmGripper::modbus(const ToolModbusRequest& request) {
  if (request.function == kModbusReadHolding) {
    std::vector<std::uint16_t> values;
    for (std::uint16_t i = 0; i < request.count; ++i) {
      const auto value = read(static_cast<std::uint16_t>(request.address + i));
      if (!value) return encode_tool_modbus_exception(request.slave, request.function, kIllegalAddress);
      values.push_back(*value);
    }
    return encode_tool_modbus_read_reply(request.slave, values);
  }
  for (std::uint16_t i = 0; i < request.count; ++i) {
    if (!write(static_cast<std::uint16_t>(request.address + i), request.values[i])) {
      return encode_tool_modbus_exception(request.slave, request.function, kIllegalValue);
    }
  }
  return encode_tool_modbus_write_reply(request.slave, request.address, request.count);
}

void XarmGripper::set_error(int code) {
  error_ = code;
  if (code != 0) enabled_ = false;
}

nlohmann::json XarmGripper::state() const {
  return {{"enabled", enabled_},
          {"mode", mode_},
          {"speed_rpm", speed_rpm_},
          {"position_pulses", position_},
          {"target_pulses", target_},
          {"error", error_},
          {"object_pulses", object_pulses_},
          {"status", read(address_of(GripperRegister::kStatus)).value_or(0)}};
}

}  // namespace robotd::xarm::sim
