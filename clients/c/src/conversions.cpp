#include "conversions.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <iterator>
#include <string>
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
static_assert(ROBOTD_LOW_RATE_WARN == static_cast<int>(LowRateAction::kWarn));
static_assert(ROBOTD_LOW_RATE_FALLBACK == static_cast<int>(LowRateAction::kFallback));

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
  copy_text(info.kinematic_model, out.kinematic_model);
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

void to_c(const TickState& state, robotd_tick_state& out) {
  out = robotd_tick_state{};
  copy_text(state.header.frame_id, out.device);
  out.tick = state.tick;
  out.stamp_ns = state.header.stamp.to_ns();
  out.deadline_steady_ns = state.deadline_steady_ns;
  out.period_ns = state.period_ns;
  out.state_ready_steady_ns = state.state_ready_steady_ns;
  out.published_steady_ns = state.published_steady_ns;
  out.state = static_cast<robotd_device_state>(state.state);
  out.joint_count = joint_count(state.position.size());
  copy_values(state.position, out.position, out.joint_count);
  copy_values(state.velocity, out.velocity, out.joint_count);
  copy_values(state.effort, out.effort, out.joint_count);
  out.has_imu = state.has_imu;
  const Quaternion& q = state.imu_orientation;
  std::ranges::copy(std::array{q.x, q.y, q.z, q.w}, std::begin(out.imu_orientation));
  const Vector3& w = state.imu_angular_velocity;
  std::ranges::copy(std::array{w.x, w.y, w.z}, std::begin(out.imu_angular_velocity));
  const Vector3& a = state.imu_linear_acceleration;
  std::ranges::copy(std::array{a.x, a.y, a.z}, std::begin(out.imu_linear_acceleration));
}

void to_c(const SessionInfo& info, robotd_session_info& out) {
  out = robotd_session_info{};
  copy_text(info.uuid, out.session_id);  // SessionInfo.uuid holds the public id
  copy_text(info.node_name, out.node_name);
  copy_text(info.device, out.device);
  out.commands_accepted = info.commands_accepted;
  out.closed_loop = info.closed_loop;
  out.ticks_to_answer = info.ticks_to_answer;
  out.ticks_answered_in_time = info.ticks_answered_in_time;
  out.ticks_answered_late = info.ticks_answered_late;
  out.ticks_unanswered = info.ticks_unanswered;
  out.command_success_rate = info.command_success_rate;
  out.min_command_success_rate = info.min_command_success_rate;
  out.on_low_success_rate = static_cast<robotd_low_rate_action>(info.on_low_success_rate);
  out.success_rate_low = info.success_rate_low;
}

TickState tick_of(const robotd_tick_state& state) {
  TickState tick;
  tick.header.frame_id = std::string(state.device, strnlen(state.device, sizeof state.device));
  tick.tick = state.tick;
  return tick;
}

}  // namespace robotd::c
