// The robotd DDS interface as plain C++ values. One struct per message in robotd_msgs.idl;
// the wire library converts them to and from the idlc-generated C types. Units are SI and
// radians, as on the wire.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace robotd {

/// How a session commands its motors (RequestControl.control_mode).
enum class ControlMode : std::int32_t { kPosition = 0, kTorque = 1, kMixed = 2 };

/// What happens to a session's motors on timeout or release (default_behavior, release_mode).
enum class Behavior : std::int32_t { kKeep = 0, kDamping = 1, kZeroTorque = 2 };

/// What robotd does when a closed-loop session's command success rate falls below the minimum
/// it asked for (RequestControl.on_low_success_rate).
enum class LowRateAction : std::int32_t { kWarn = 0, kFallback = 1 };

/// DeviceStatus.state.
enum class DeviceState : std::uint8_t {
  kConnecting = 0,
  kRunning = 1,
  kFault = 2,
  kEstop = 3,
  kMaintenance = 4,  // recover or reset_zero in progress: commands and new sessions refused
  kStopped = 5,
};

std::string_view to_string(ControlMode mode);
std::string_view to_string(Behavior behavior);
std::string_view to_string(DeviceState state);
std::optional<ControlMode> parse_control_mode(std::string_view text);  // "POSITION", "position", "0"
std::string_view to_string(LowRateAction action);
std::optional<Behavior> parse_behavior(std::string_view text);              // "KEEP", "damping", "2"
std::optional<LowRateAction> parse_low_rate_action(std::string_view text);  // "WARN", "fallback", "1"
bool is_valid(ControlMode mode);
bool is_valid(Behavior behavior);
bool is_valid(LowRateAction action);

struct Time {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  static Time from_ns(std::int64_t ns);
  std::int64_t to_ns() const;
};

struct Header {
  Time stamp;
  std::string frame_id;
};

struct ControlCommand {
  Header header;
  std::string uuid;
  std::vector<std::int32_t> motor_ids;
  std::vector<float> positions;     // rad
  std::vector<float> velocities;    // rad/s
  std::vector<float> kp;            // N·m/rad
  std::vector<float> kd;            // N·m·s/rad
  std::vector<float> torques;       // N·m
  std::string device;               // "" = the session's device
  std::int64_t sent_steady_ns = 0;  // sender's CLOCK_MONOTONIC at publish, 0 = unknown
  std::uint64_t answers_tick = 0;   // the tick whose TickState this answers (closed loop), 0 = none
};

struct JointState {
  Header header;  // frame_id = device name
  std::vector<std::string> name;
  std::vector<double> position;  // rad
  std::vector<double> velocity;  // rad/s
  std::vector<double> effort;    // N·m
};

struct Vector3 {
  double x = 0, y = 0, z = 0;
};
struct Quaternion {
  double x = 0, y = 0, z = 0, w = 1;
};
/// An end effector's pose (geometry_msgs/PoseStamped); frame_id = device name.
struct PoseStamped {
  Header header;
  Vector3 position;  // m
  Quaternion orientation;
};

struct Imu {
  Header header;  // frame_id = device name
  Quaternion orientation;
  Vector3 angular_velocity;     // rad/s
  Vector3 linear_acceleration;  // m/s²
};

/// What one tick of a device's loop measured, published on /<device>/tick_state right after
/// the tick. A closed-loop client answers it (ControlCommand.answers_tick = tick).
struct TickState {
  Header header;                           // stamp: the tick's deadline (CLOCK_REALTIME); frame_id = device
  std::uint64_t tick = 0;                  // 1, 2, ...
  std::int64_t deadline_steady_ns = 0;     // the tick's deadline, CLOCK_MONOTONIC
  std::int64_t period_ns = 0;              // the next tick is due at deadline + period
  std::int64_t state_ready_steady_ns = 0;  // the loop handed the state over (CLOCK_MONOTONIC)
  std::int64_t published_steady_ns = 0;    // robotd wrote the sample (CLOCK_MONOTONIC)
  DeviceState state = DeviceState::kConnecting;
  std::vector<double> position;  // rad, one per joint
  std::vector<double> velocity;  // rad/s
  std::vector<double> effort;    // N·m
  bool has_imu = false;
  Quaternion imu_orientation;
  Vector3 imu_angular_velocity;     // rad/s
  Vector3 imu_linear_acceleration;  // m/s²
};

/// A game controller's state (robotd_msgs/Joy), the PI Plus /hightorque_joy field for field
/// (header last). Sticks and d-pad in -1..1, positive = left / up; triggers 0 (released) ..
/// 1 (pressed); buttons 0 or 1. All zero = neutral.
struct Joy {
  float l_horizontal = 0, l_vertical = 0, lt = 0;
  float r_horizontal = 0, r_vertical = 0, rt = 0;
  float dpad_horizontal = 0, dpad_vertical = 0;
  float a = 0, b = 0, x = 0, y = 0;
  float lb = 0, rb = 0, back = 0, start = 0, center = 0, l = 0, r = 0;
  Header header;  // frame_id = the joystick's device path
};

/// The PI Plus policy / data stream (robotd_msgs/PolicyData): what a policy observes and
/// outputs, one data_type per sample ("state_q", "obs", "input", "action", "output_q", ...).
struct PolicyData {
  Header header;
  std::string data_type;
  std::vector<double> data;
};

struct SessionInfo {
  std::string uuid;  // the session's public id, not its uuid (the name is the PI Plus's; see SessionStatus)
  std::string node_name;
  std::string device;
  std::vector<std::int32_t> motor_ids;
  ControlMode control_mode = ControlMode::kPosition;
  Behavior default_behavior = Behavior::kKeep;
  Behavior applied_behavior = Behavior::kKeep;  // what the device really does on timeout
  std::int32_t timeout_ms = 0;
  std::int32_t time_left_ms = 0;
  Time granted_at;  // CLOCK_REALTIME
  std::uint64_t commands_accepted = 0;
  std::string policy_name;  // as the session named them in RequestControl
  std::string policy_file_name;
  // Closed loop (sessions that answer ticks): each tick whose state the session was to answer,
  // since its first answer, is answered in time, late, or never.
  bool closed_loop = false;
  std::uint64_t ticks_to_answer = 0;
  std::uint64_t ticks_answered_in_time = 0;
  std::uint64_t ticks_answered_late = 0;
  std::uint64_t ticks_unanswered = 0;
  float command_success_rate = 0;      // in time / to answer over the last kSuccessRateWindowTicks (0..1)
  float min_command_success_rate = 0;  // 0 = none
  LowRateAction on_low_success_rate = LowRateAction::kWarn;
  bool success_rate_low = false;  // below the minimum now
};

/// The ticks SessionInfo.command_success_rate covers (libfranka's control_command_success_rate
/// covers its last 100 commands likewise).
inline constexpr std::uint32_t kSuccessRateWindowTicks = 100;

/// One service's requests as robotd's DDS surface saw them.
struct ServiceCounters {
  std::string service;  // "request_control", ...
  std::uint64_t requests = 0;
  std::uint64_t refused = 0;    // replies with success = false, oversized requests included
  std::uint64_t oversized = 0;  // requests with a field beyond its limit (refused, but an e-stop's words are cut)
};

/// What robotd's DDS surface saw that no device's CommandCounters can hold.
struct SurfaceCounters {
  std::uint64_t commands_unattributed = 0;  // naming no active session and no device robotd has
  std::uint64_t dds_log_messages = 0;       // warnings and errors of the DDS layer (a malformed sample, ...)
  std::vector<ServiceCounters> services;
};

struct SessionStatus {
  Header header;
  std::string state;  // "idle" or "active"
  // The newest session's that named a policy (the PI Plus runs one policy at a time; every
  // session's own are in `sessions`).
  std::string policy_name;
  std::string policy_file_name;
  // The PI Plus's parallel arrays. active_uuids holds each session's public id: a session's
  // uuid is its capability and only its holder knows it (docs/security.md).
  std::vector<std::string> active_uuids;
  std::vector<std::string> node_names;
  std::vector<std::int32_t> motor_counts;
  std::vector<SessionInfo> sessions;
  SurfaceCounters surface;
};

struct LoopStatistics {
  double rate_hz = 0;
  bool realtime = false;  // SCHED_FIFO granted
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;
  std::uint32_t window_ticks = 0;
  float period_p50_us = 0, period_p99_us = 0, period_max_us = 0;
  float wake_latency_p50_us = 0, wake_latency_p99_us = 0, wake_latency_max_us = 0;
  float execution_p50_us = 0, execution_p99_us = 0, execution_max_us = 0;
  std::int64_t rt_heap_allocations = -1;     // -1 = not measured (no allocation probe loaded)
  std::int64_t tick_deadline_steady_ns = 0;  // a recent tick's deadline: ticks are due at it + n × period_ns
  std::int64_t period_ns = 0;
};

struct CommandCounters {
  std::uint64_t received = 0;
  std::uint64_t accepted = 0;
  std::uint64_t clamped = 0;
  std::uint64_t rejected_unknown_session = 0;
  std::uint64_t rejected_wrong_device = 0;
  std::uint64_t rejected_not_owner = 0;
  std::uint64_t rejected_unknown_motor = 0;
  std::uint64_t rejected_malformed = 0;
  std::uint64_t rejected_non_finite = 0;
  std::uint64_t rejected_out_of_range = 0;
  std::uint64_t rejected_estop = 0;
  std::uint64_t rejected_fault = 0;
  std::uint64_t dropped_stale = 0;
  std::uint64_t rejected_total() const;
};

struct KeyValue {
  std::string key;
  std::string value;
};

struct DeviceStatus {
  Header header;
  std::string device;
  std::string driver;
  DeviceState state = DeviceState::kConnecting;
  std::string state_text;
  std::int32_t fault_code = 0;
  std::string fault_text;
  bool estop_engaged = false;
  LoopStatistics loop;
  CommandCounters commands;
  std::vector<KeyValue> driver_values;
  std::uint64_t joint_states_published = 0;  // /joint_states samples of this device written so far
};

struct DeviceInfo {
  std::string name;
  std::string driver;
  std::string driver_version;
  std::string model;
  std::string kinematic_model;  // the arm model clients plan with (robotd::kinematics), "" when none
  double rate_hz = 0;
  double native_rate_hz = 0;
  std::vector<std::string> joint_names;
  std::vector<double> position_min;      // rad
  std::vector<double> position_max;      // rad
  std::vector<double> velocity_max;      // rad/s
  std::vector<double> acceleration_max;  // rad/s²
  std::vector<double> effort_max;        // N·m
  std::vector<std::string> control_modes;
  std::vector<std::int32_t> behavior_map;  // applied behaviour for KEEP, DAMPING, ZERO_TORQUE
  std::vector<std::string> ops;            // device_call ops, "name: help" (+ kNeedsFreeMotorsMark)
  DeviceState state = DeviceState::kConnecting;
};

/// Ends an op's line in DeviceInfo.ops when robotd refuses the op while a session holds a motor.
inline constexpr std::string_view kNeedsFreeMotorsMark = " [needs free motors]";

// Services. Each request/response pair mirrors robotd_msgs/srv/<Name>.srv.

struct RequestControlRequest {
  std::string node_name;
  std::vector<std::int32_t> motor_ids;  // empty = every motor of the device
  ControlMode control_mode = ControlMode::kPosition;
  Behavior default_behavior = Behavior::kDamping;
  std::int32_t timeout_ms = 1000;
  std::vector<float> default_kp;  // empty or one per motor
  std::vector<float> default_kd;
  std::string device;  // "" = the only device
  // Who will command, shown in /session_status: e.g. "walk" and "walk_v3.onnx" ("" = none).
  std::string policy_name;
  std::string policy_file_name;
  // Closed loop: the least fraction of ticks answered in time (0..1, 0 = none) over the last
  // kSuccessRateWindowTicks, and what robotd does below it.
  float min_command_success_rate = 0;
  LowRateAction on_low_success_rate = LowRateAction::kWarn;
};
struct RequestControlResponse {
  bool success = false;
  std::string message;
  std::string uuid;  // the session's capability: put it in every command, keep it to yourself
  std::vector<std::int32_t> motor_ids;
  Behavior applied_behavior = Behavior::kKeep;
  std::string device;      // the device granted
  std::string session_id;  // the session's public id, as /session_status and refusals name it
};

struct ReleaseControlRequest {
  std::string node_name;
  std::string uuid;
  Behavior release_mode = Behavior::kKeep;
};
struct ReleaseControlResponse {
  bool success = false;
  std::string message;
  Behavior applied_behavior = Behavior::kKeep;
};

struct GetAvailableMotorsRequest {
  std::string node_name;
  std::string device;
};
struct GetAvailableMotorsResponse {
  std::vector<std::int32_t> motor_ids;
  std::vector<std::string> motor_names;
  bool success = false;
  std::string message;
};

struct ResetZeroRequest {
  std::string device;
  std::vector<std::int32_t> motor_ids;  // empty = all
  std::int32_t timeout_ms = 10000;
};
struct ResetZeroResponse {
  bool success = false;
  std::string message;
};

struct EstopRequest {
  std::string node_name;
  std::string device;  // "" = every device
  bool engage = true;  // false = reset
  std::string reason;
};
struct EstopResponse {
  bool success = false;
  std::string message;
};

struct ListDevicesRequest {
  std::string node_name;
};
struct ListDevicesResponse {
  std::vector<DeviceInfo> devices;
};

struct DeviceCallRequest {
  std::string device;
  std::string op;
  std::string args_json = "{}";
};
struct DeviceCallResponse {
  bool success = false;
  std::string message;
  std::string result_json;
};

}  // namespace robotd
