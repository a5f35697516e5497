#include "conversions.hpp"

#include <algorithm>
#include <cstddef>
#include <string_view>
#include <vector>

namespace robotd::c {
namespace {

// The C enums are the C++ ones, value for value.
static_assert(ROBOTD_MODE_POSITION == static_cast<int>(ControlMode::kPosition));
static_assert(ROBOTD_MODE_TORQUE == static_cast<int>(ControlMode::kTorque));
static_assert(ROBOTD_MODE_MIXED == static_cast<int>(ControlMode::kMixed));
static_assert(ROBOTD_BEHAVIOR_KEEP == static_cast<int>(Behavior::kKeep));
static_assert(ROBOTD_BEHAVIOR_DAMPING == static_cast<int>(Behavior::kDamping));
static_assert(ROBOTD_BEHAVIOR_ZERO_TORQUE == static_cast<int>(Behavior::kZeroTorque));
static_assert(ROBOTD_DEVICE_CONNECTING == static_cast<int>(DeviceState::kConnecting));
static_assert(ROBOTD_DEVICE_RUNNING == static_cast<int>(DeviceState::kRunning));
static_assert(ROBOTD_DEVICE_FAULT == static_cast<int>(DeviceState::kFault));
static_assert(ROBOTD_DEVICE_ESTOP == static_cast<int>(DeviceState::kEstop));
static_assert(ROBOTD_DEVICE_MAINTENANCE == static_cast<int>(DeviceState::kMaintenance));
static_assert(ROBOTD_DEVICE_STOPPED == static_cast<int>(DeviceState::kStopped));

template <std::size_t kCapacity>
void copy_text(std::string_view text, char (&field)[kCapacity]) {
  std::size_t length = std::min(text.size(), kCapacity - 1);
  // Never cut inside a UTF-8 sequence: step back over continuation bytes (10xxxxxx).
  if (length < text.size()) {
    while (length > 0 && (static_cast<unsigned char>(text[length]) & 0xC0U) == 0x80U) --length;
  }
  text.copy(field, length);
  field[length] = '\0';
}

// Up to `count` values; a shorter vector leaves the rest as they are (zero).
void copy_values(const std::vector<double>& values, double (&field)[ROBOTD_MAX_JOINTS], std::size_t count) {
  std::copy_n(values.begin(), std::min(values.size(), count), field);
}

std::size_t joint_count(std::size_t count) { return std::min<std::size_t>(count, ROBOTD_MAX_JOINTS); }

}  // namespace

void to_c(const DeviceInfo& info, robotd_device_info& out) {
  out = robotd_device_info{};
  copy_text(info.name, out.name);
  copy_text(info.driver, out.driver);
  copy_text(info.model, out.model);
  out.state = static_cast<robotd_device_state>(info.state);
  out.rate_hz = info.rate_hz;
  out.joint_count = joint_count(info.joint_names.size());
  for (std::size_t j = 0; j < out.joint_count; ++j) copy_text(info.joint_names[j], out.joint_names[j]);
  copy_values(info.position_min, out.position_min, out.joint_count);
  copy_values(info.position_max, out.position_max, out.joint_count);
  copy_values(info.velocity_max, out.velocity_max, out.joint_count);
  copy_values(info.effort_max, out.effort_max, out.joint_count);
}

void to_c(const JointState& state, robotd_joint_state& out) {
  out = robotd_joint_state{};
  copy_text(state.header.frame_id, out.device);
  out.stamp_ns = state.header.stamp.to_ns();
  out.joint_count = joint_count(state.name.size());
  for (std::size_t j = 0; j < out.joint_count; ++j) copy_text(state.name[j], out.names[j]);
  copy_values(state.position, out.position, out.joint_count);
  copy_values(state.velocity, out.velocity, out.joint_count);
  copy_values(state.effort, out.effort, out.joint_count);
}

void to_c(const DeviceStatus& status, robotd_device_status& out) {
  out = robotd_device_status{};
  copy_text(status.device, out.device);
  out.stamp_ns = status.header.stamp.to_ns();
  out.state = static_cast<robotd_device_state>(status.state);
  copy_text(status.state_text, out.state_text);
  out.fault_code = status.fault_code;
  copy_text(status.fault_text, out.fault_text);
  out.estop_engaged = status.estop_engaged;
  out.loop_period_p50_us = status.loop.period_p50_us;
  out.loop_period_p99_us = status.loop.period_p99_us;
  out.loop_period_max_us = status.loop.period_max_us;
  out.loop_overruns = status.loop.overruns;
  out.commands_accepted = status.commands.accepted;
  out.commands_rejected = status.commands.rejected_total();
}

}  // namespace robotd::c
