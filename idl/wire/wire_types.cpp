#include "wire/wire_types.hpp"

#include <algorithm>

namespace robotd::wire {
namespace {

void header_to_c(const Header& in, std_msgs_msg_dds__Header_& out) {
  out.stamp.sec = in.stamp.sec;
  out.stamp.nanosec = in.stamp.nanosec;
  out.frame_id = c_string(in.frame_id);
}

Header header_from_c(const std_msgs_msg_dds__Header_& in) {
  return Header{Time{in.stamp.sec, in.stamp.nanosec}, copy_string(in.frame_id)};
}

template <class Enum>
Enum enum_from_c(std::int32_t value) {
  return static_cast<Enum>(value);
}
template <class Enum>
std::int32_t enum_to_c(Enum value) {
  return static_cast<std::int32_t>(value);
}

// The Joy axes and buttons, which the C and the C++ struct name alike.
template <class From, class To>
void copy_joy_values(const From& in, To& out) {
  out.l_horizontal = in.l_horizontal;
  out.l_vertical = in.l_vertical;
  out.lt = in.lt;
  out.r_horizontal = in.r_horizontal;
  out.r_vertical = in.r_vertical;
  out.rt = in.rt;
  out.dpad_horizontal = in.dpad_horizontal;
  out.dpad_vertical = in.dpad_vertical;
  out.a = in.a;
  out.b = in.b;
  out.x = in.x;
  out.y = in.y;
  out.lb = in.lb;
  out.rb = in.rb;
  out.back = in.back;
  out.start = in.start;
  out.center = in.center;
  out.l = in.l;
  out.r = in.r;
}

// The closed-loop fields of SessionInfo that the C and the C++ struct name and type alike.
template <class From, class To>
void copy_answer_counts(const From& in, To& out) {
  out.closed_loop = in.closed_loop;
  out.ticks_to_answer = in.ticks_to_answer;
  out.ticks_answered_in_time = in.ticks_answered_in_time;
  out.ticks_answered_late = in.ticks_answered_late;
  out.ticks_unanswered = in.ticks_unanswered;
  out.command_success_rate = in.command_success_rate;
  out.min_command_success_rate = in.min_command_success_rate;
  out.success_rate_low = in.success_rate_low;
}

void session_info_to_c(const SessionInfo& in, robotd_msgs_msg_dds__SessionInfo_& out) {
  out.uuid = c_string(in.uuid);
  out.node_name = c_string(in.node_name);
  out.device = c_string(in.device);
  view_sequence(out.motor_ids, in.motor_ids);
  out.control_mode = enum_to_c(in.control_mode);
  out.default_behavior = enum_to_c(in.default_behavior);
  out.applied_behavior = enum_to_c(in.applied_behavior);
  out.timeout_ms = in.timeout_ms;
  out.time_left_ms = in.time_left_ms;
  out.granted_at.sec = in.granted_at.sec;
  out.granted_at.nanosec = in.granted_at.nanosec;
  out.commands_accepted = in.commands_accepted;
  out.policy_name = c_string(in.policy_name);
  out.policy_file_name = c_string(in.policy_file_name);
  copy_answer_counts(in, out);
  out.on_low_success_rate = enum_to_c(in.on_low_success_rate);
}

void surface_to_c(const SurfaceCounters& in, robotd_msgs_msg_dds__SurfaceCounters_& out, CArena& arena) {
  out.commands_unattributed = in.commands_unattributed;
  out.dds_log_messages = in.dds_log_messages;
  auto* services = arena.array<robotd_msgs_msg_dds__ServiceCounters_>(in.services.size());
  for (std::size_t i = 0; i < in.services.size(); ++i) {
    const ServiceCounters& service = in.services[i];
    services[i] = {c_string(service.service), service.requests, service.refused, service.oversized};
  }
  out.services._length = out.services._maximum = static_cast<std::uint32_t>(in.services.size());
  out.services._buffer = services;
  out.services._release = false;
}

SurfaceCounters surface_from_c(const robotd_msgs_msg_dds__SurfaceCounters_& in) {
  SurfaceCounters out{in.commands_unattributed, in.dds_log_messages, {}};
  for (std::uint32_t i = 0; i < in.services._length; ++i) {
    const auto& service = in.services._buffer[i];
    out.services.push_back({copy_string(service.service), service.requests, service.refused, service.oversized});
  }
  return out;
}

SessionInfo session_info_from_c(const robotd_msgs_msg_dds__SessionInfo_& in) {
  SessionInfo out;
  out.uuid = copy_string(in.uuid);
  out.node_name = copy_string(in.node_name);
  out.device = copy_string(in.device);
  out.motor_ids = copy_sequence<std::int32_t>(in.motor_ids);
  out.control_mode = enum_from_c<ControlMode>(in.control_mode);
  out.default_behavior = enum_from_c<Behavior>(in.default_behavior);
  out.applied_behavior = enum_from_c<Behavior>(in.applied_behavior);
  out.timeout_ms = in.timeout_ms;
  out.time_left_ms = in.time_left_ms;
  out.granted_at = Time{in.granted_at.sec, in.granted_at.nanosec};
  out.commands_accepted = in.commands_accepted;
  out.policy_name = copy_string(in.policy_name);
  out.policy_file_name = copy_string(in.policy_file_name);
  copy_answer_counts(in, out);
  out.on_low_success_rate = enum_from_c<LowRateAction>(in.on_low_success_rate);
  return out;
}

void device_info_to_c(const DeviceInfo& in, robotd_msgs_msg_dds__DeviceInfo_& out, CArena& arena) {
  out.name = c_string(in.name);
  out.driver = c_string(in.driver);
  out.driver_version = c_string(in.driver_version);
  out.model = c_string(in.model);
  out.kinematic_model = c_string(in.kinematic_model);
  out.rate_hz = in.rate_hz;
  out.native_rate_hz = in.native_rate_hz;
  view_string_sequence(out.joint_names, in.joint_names, arena);
  view_sequence(out.position_min, in.position_min);
  view_sequence(out.position_max, in.position_max);
  view_sequence(out.velocity_max, in.velocity_max);
  view_sequence(out.acceleration_max, in.acceleration_max);
  view_sequence(out.effort_max, in.effort_max);
  view_string_sequence(out.control_modes, in.control_modes, arena);
  view_sequence(out.behavior_map, in.behavior_map);
  view_string_sequence(out.ops, in.ops, arena);
  out.state = static_cast<std::uint8_t>(in.state);
}

DeviceInfo device_info_from_c(const robotd_msgs_msg_dds__DeviceInfo_& in) {
  DeviceInfo out;
  out.name = copy_string(in.name);
  out.driver = copy_string(in.driver);
  out.driver_version = copy_string(in.driver_version);
  out.model = copy_string(in.model);
  out.kinematic_model = copy_string(in.kinematic_model);
  out.rate_hz = in.rate_hz;
  out.native_rate_hz = in.native_rate_hz;
  out.joint_names = copy_string_sequence(in.joint_names);
  out.position_min = copy_sequence<double>(in.position_min);
  out.position_max = copy_sequence<double>(in.position_max);
  out.velocity_max = copy_sequence<double>(in.velocity_max);
  out.acceleration_max = copy_sequence<double>(in.acceleration_max);
  out.effort_max = copy_sequence<double>(in.effort_max);
  out.control_modes = copy_string_sequence(in.control_modes);
  out.behavior_map = copy_sequence<std::int32_t>(in.behavior_map);
  out.ops = copy_string_sequence(in.ops);
  out.state = static_cast<DeviceState>(in.state);
  return out;
}

}  // namespace

// --- topics ---------------------------------------------------------------------------------

const dds_topic_descriptor_t& Wire<ControlCommand>::descriptor() { return robotd_msgs_msg_dds__ControlCommand__desc; }

void Wire<ControlCommand>::to_c(const ControlCommand& in, C& out, CArena& /*arena*/) {
  header_to_c(in.header, out.header);
  out.uuid = c_string(in.uuid);
  view_sequence(out.motor_ids, in.motor_ids);
  view_sequence(out.positions, in.positions);
  view_sequence(out.velocities, in.velocities);
  view_sequence(out.kp, in.kp);
  view_sequence(out.kd, in.kd);
  view_sequence(out.torques, in.torques);
  out.device = c_string(in.device);
  out.sent_steady_ns = in.sent_steady_ns;
  out.answers_tick = in.answers_tick;
}

ControlCommand Wire<ControlCommand>::from_c(const C& in) {
  ControlCommand out;
  out.header = header_from_c(in.header);
  out.uuid = copy_string(in.uuid);
  out.motor_ids = copy_sequence<std::int32_t>(in.motor_ids);
  out.positions = copy_sequence<float>(in.positions);
  out.velocities = copy_sequence<float>(in.velocities);
  out.kp = copy_sequence<float>(in.kp);
  out.kd = copy_sequence<float>(in.kd);
  out.torques = copy_sequence<float>(in.torques);
  out.device = copy_string(in.device);
  out.sent_steady_ns = in.sent_steady_ns;
  out.answers_tick = in.answers_tick;
  return out;
}

const dds_topic_descriptor_t& Wire<TickState>::descriptor() { return robotd_msgs_msg_dds__TickState__desc; }

void Wire<TickState>::to_c(const TickState& in, C& out, CArena& /*arena*/) {
  header_to_c(in.header, out.header);
  out.tick = in.tick;
  out.deadline_steady_ns = in.deadline_steady_ns;
  out.period_ns = in.period_ns;
  out.state_ready_steady_ns = in.state_ready_steady_ns;
  out.published_steady_ns = in.published_steady_ns;
  out.state = static_cast<std::uint8_t>(in.state);
  view_sequence(out.position, in.position);
  view_sequence(out.velocity, in.velocity);
  view_sequence(out.effort, in.effort);
  out.has_imu = in.has_imu;
  const Quaternion& q = in.imu_orientation;
  out.imu_orientation = {q.x, q.y, q.z, q.w};
  out.imu_angular_velocity = {in.imu_angular_velocity.x, in.imu_angular_velocity.y, in.imu_angular_velocity.z};
  out.imu_linear_acceleration = {in.imu_linear_acceleration.x, in.imu_linear_acceleration.y,
                                 in.imu_linear_acceleration.z};
}

TickState Wire<TickState>::from_c(const C& in) {
  TickState out;
  out.header = header_from_c(in.header);
  out.tick = in.tick;
  out.deadline_steady_ns = in.deadline_steady_ns;
  out.period_ns = in.period_ns;
  out.state_ready_steady_ns = in.state_ready_steady_ns;
  out.published_steady_ns = in.published_steady_ns;
  out.state = static_cast<DeviceState>(in.state);
  out.position = copy_sequence<double>(in.position);
  out.velocity = copy_sequence<double>(in.velocity);
  out.effort = copy_sequence<double>(in.effort);
  out.has_imu = in.has_imu;
  const auto& q = in.imu_orientation;
  out.imu_orientation = {q.x, q.y, q.z, q.w};
  out.imu_angular_velocity = {in.imu_angular_velocity.x, in.imu_angular_velocity.y, in.imu_angular_velocity.z};
  out.imu_linear_acceleration = {in.imu_linear_acceleration.x, in.imu_linear_acceleration.y,
                                 in.imu_linear_acceleration.z};
  return out;
}

const dds_topic_descriptor_t& Wire<JointState>::descriptor() { return sensor_msgs_msg_dds__JointState__desc; }

void Wire<JointState>::to_c(const JointState& in, C& out, CArena& arena) {
  header_to_c(in.header, out.header);
  view_string_sequence(out.name, in.name, arena);
  view_sequence(out.position, in.position);
  view_sequence(out.velocity, in.velocity);
  view_sequence(out.effort, in.effort);
}

JointState Wire<JointState>::from_c(const C& in) {
  JointState out;
  out.header = header_from_c(in.header);
  out.name = copy_string_sequence(in.name);
  out.position = copy_sequence<double>(in.position);
  out.velocity = copy_sequence<double>(in.velocity);
  out.effort = copy_sequence<double>(in.effort);
  return out;
}

const dds_topic_descriptor_t& Wire<Imu>::descriptor() { return sensor_msgs_msg_dds__Imu__desc; }

void Wire<Imu>::to_c(const Imu& in, C& out, CArena& /*arena*/) {
  header_to_c(in.header, out.header);
  out.orientation = {in.orientation.x, in.orientation.y, in.orientation.z, in.orientation.w};
  out.angular_velocity = {in.angular_velocity.x, in.angular_velocity.y, in.angular_velocity.z};
  out.linear_acceleration = {in.linear_acceleration.x, in.linear_acceleration.y, in.linear_acceleration.z};
  // ROS convention: covariance all zero = unknown.
  std::fill(std::begin(out.orientation_covariance), std::end(out.orientation_covariance), 0.0);
  std::fill(std::begin(out.angular_velocity_covariance), std::end(out.angular_velocity_covariance), 0.0);
  std::fill(std::begin(out.linear_acceleration_covariance), std::end(out.linear_acceleration_covariance), 0.0);
}

Imu Wire<Imu>::from_c(const C& in) {
  Imu out;
  out.header = header_from_c(in.header);
  out.orientation = {in.orientation.x, in.orientation.y, in.orientation.z, in.orientation.w};
  out.angular_velocity = {in.angular_velocity.x, in.angular_velocity.y, in.angular_velocity.z};
  out.linear_acceleration = {in.linear_acceleration.x, in.linear_acceleration.y, in.linear_acceleration.z};
  return out;
}

const dds_topic_descriptor_t& Wire<PoseStamped>::descriptor() { return geometry_msgs_msg_dds__PoseStamped__desc; }

void Wire<PoseStamped>::to_c(const PoseStamped& in, C& out, CArena& /*arena*/) {
  header_to_c(in.header, out.header);
  out.pose.position = {in.position.x, in.position.y, in.position.z};
  out.pose.orientation = {in.orientation.x, in.orientation.y, in.orientation.z, in.orientation.w};
}

PoseStamped Wire<PoseStamped>::from_c(const C& in) {
  PoseStamped out;
  out.header = header_from_c(in.header);
  out.position = {in.pose.position.x, in.pose.position.y, in.pose.position.z};
  out.orientation = {in.pose.orientation.x, in.pose.orientation.y, in.pose.orientation.z, in.pose.orientation.w};
  return out;
}

const dds_topic_descriptor_t& Wire<Vector3>::descriptor() { return geometry_msgs_msg_dds__Vector3__desc; }
void Wire<Vector3>::to_c(const Vector3& in, C& out, CArena& /*arena*/) { out = {in.x, in.y, in.z}; }
Vector3 Wire<Vector3>::from_c(const C& in) { return {in.x, in.y, in.z}; }

const dds_topic_descriptor_t& Wire<Quaternion>::descriptor() { return geometry_msgs_msg_dds__Quaternion__desc; }
void Wire<Quaternion>::to_c(const Quaternion& in, C& out, CArena& /*arena*/) { out = {in.x, in.y, in.z, in.w}; }
Quaternion Wire<Quaternion>::from_c(const C& in) { return {in.x, in.y, in.z, in.w}; }

const dds_topic_descriptor_t& Wire<Joy>::descriptor() { return robotd_msgs_msg_dds__Joy__desc; }

void Wire<Joy>::to_c(const Joy& in, C& out, CArena& /*arena*/) {
  copy_joy_values(in, out);
  header_to_c(in.header, out.header);
}

Joy Wire<Joy>::from_c(const C& in) {
  Joy out;
  copy_joy_values(in, out);
  out.header = header_from_c(in.header);
  return out;
}

const dds_topic_descriptor_t& Wire<PolicyData>::descriptor() { return robotd_msgs_msg_dds__PolicyData__desc; }

void Wire<PolicyData>::to_c(const PolicyData& in, C& out, CArena& /*arena*/) {
  header_to_c(in.header, out.header);
  out.data_type = c_string(in.data_type);
  view_sequence(out.data, in.data);
}

PolicyData Wire<PolicyData>::from_c(const C& in) {
  return PolicyData{header_from_c(in.header), copy_string(in.data_type), copy_sequence<double>(in.data)};
}

const dds_topic_descriptor_t& Wire<SessionStatus>::descriptor() { return robotd_msgs_msg_dds__SessionStatus__desc; }

void Wire<SessionStatus>::to_c(const SessionStatus& in, C& out, CArena& arena) {
  header_to_c(in.header, out.header);
  out.state = c_string(in.state);
  out.policy_name = c_string(in.policy_name);
  out.policy_file_name = c_string(in.policy_file_name);
  view_string_sequence(out.active_uuids, in.active_uuids, arena);
  view_string_sequence(out.node_names, in.node_names, arena);
  view_sequence(out.motor_counts, in.motor_counts);
  auto* sessions = arena.array<robotd_msgs_msg_dds__SessionInfo_>(in.sessions.size());
  for (std::size_t i = 0; i < in.sessions.size(); ++i) session_info_to_c(in.sessions[i], sessions[i]);
  out.sessions._length = out.sessions._maximum = static_cast<std::uint32_t>(in.sessions.size());
  out.sessions._buffer = sessions;
  out.sessions._release = false;
  surface_to_c(in.surface, out.surface, arena);
}

SessionStatus Wire<SessionStatus>::from_c(const C& in) {
  SessionStatus out;
  out.header = header_from_c(in.header);
  out.state = copy_string(in.state);
  out.policy_name = copy_string(in.policy_name);
  out.policy_file_name = copy_string(in.policy_file_name);
  out.active_uuids = copy_string_sequence(in.active_uuids);
  out.node_names = copy_string_sequence(in.node_names);
  out.motor_counts = copy_sequence<std::int32_t>(in.motor_counts);
  for (std::uint32_t i = 0; i < in.sessions._length; ++i)
    out.sessions.push_back(session_info_from_c(in.sessions._buffer[i]));
  out.surface = surface_from_c(in.surface);
  return out;
}

const dds_topic_descriptor_t& Wire<DeviceStatus>::descriptor() { return robotd_msgs_msg_dds__DeviceStatus__desc; }

void Wire<DeviceStatus>::to_c(const DeviceStatus& in, C& out, CArena& arena) {
  header_to_c(in.header, out.header);
  out.device = c_string(in.device);
  out.driver = c_string(in.driver);
  out.state = static_cast<std::uint8_t>(in.state);
  out.state_text = c_string(in.state_text);
  out.fault_code = in.fault_code;
  out.fault_text = c_string(in.fault_text);
  out.estop_engaged = in.estop_engaged;
  const LoopStatistics& l = in.loop;
  out.loop = {l.rate_hz,
              l.realtime,
              l.ticks,
              l.overruns,
              l.window_ticks,
              l.period_p50_us,
              l.period_p99_us,
              l.period_max_us,
              l.wake_latency_p50_us,
              l.wake_latency_p99_us,
              l.wake_latency_max_us,
              l.execution_p50_us,
              l.execution_p99_us,
              l.execution_max_us,
              l.rt_heap_allocations,
              l.tick_deadline_steady_ns,
              l.period_ns};
  const CommandCounters& c = in.commands;
  out.commands = {c.received,
                  c.accepted,
                  c.clamped,
                  c.rejected_unknown_session,
                  c.rejected_wrong_device,
                  c.rejected_not_owner,
                  c.rejected_unknown_motor,
                  c.rejected_malformed,
                  c.rejected_non_finite,
                  c.rejected_out_of_range,
                  c.rejected_estop,
                  c.rejected_fault,
                  c.dropped_stale};
  auto* values = arena.array<robotd_msgs_msg_dds__KeyValue_>(in.driver_values.size());
  for (std::size_t i = 0; i < in.driver_values.size(); ++i) {
    values[i].key = c_string(in.driver_values[i].key);
    values[i].value = c_string(in.driver_values[i].value);
  }
  out.driver_values._length = out.driver_values._maximum = static_cast<std::uint32_t>(in.driver_values.size());
  out.driver_values._buffer = values;
  out.driver_values._release = false;
  out.joint_states_published = in.joint_states_published;
}

DeviceStatus Wire<DeviceStatus>::from_c(const C& in) {
  DeviceStatus out;
  out.header = header_from_c(in.header);
  out.device = copy_string(in.device);
  out.driver = copy_string(in.driver);
  out.state = static_cast<DeviceState>(in.state);
  out.state_text = copy_string(in.state_text);
  out.fault_code = in.fault_code;
  out.fault_text = copy_string(in.fault_text);
  out.estop_engaged = in.estop_engaged;
  const auto& l = in.loop;
  out.loop = LoopStatistics{l.rate_hz,
                            l.realtime,
                            l.ticks,
                            l.overruns,
                            l.window_ticks,
                            l.period_p50_us,
                            l.period_p99_us,
                            l.period_max_us,
                            l.wake_latency_p50_us,
                            l.wake_latency_p99_us,
                            l.wake_latency_max_us,
                            l.execution_p50_us,
                            l.execution_p99_us,
                            l.execution_max_us,
                            l.rt_heap_allocations,
                            l.tick_deadline_steady_ns,
                            l.period_ns};
  const auto& c = in.commands;
  out.commands = CommandCounters{c.received,
                                 c.accepted,
                                 c.clamped,
                                 c.rejected_unknown_session,
                                 c.rejected_wrong_device,
                                 c.rejected_not_owner,
                                 c.rejected_unknown_motor,
                                 c.rejected_malformed,
                                 c.rejected_non_finite,
                                 c.rejected_out_of_range,
                                 c.rejected_estop,
                                 c.rejected_fault,
                                 c.dropped_stale};
  for (std::uint32_t i = 0; i < in.driver_values._length; ++i) {
    out.driver_values.push_back(
        {copy_string(in.driver_values._buffer[i].key), copy_string(in.driver_values._buffer[i].value)});
  }
  out.joint_states_published = in.joint_states_published;
  return out;
}

// --- services -------------------------------------------------------------------------------

const dds_topic_descriptor_t& Wire<RequestControlRequest>::descriptor() {
  return robotd_msgs_srv_dds__RequestControl_Request__desc;
}
void Wire<RequestControlRequest>::to_c(const RequestControlRequest& in, C& out, CArena& /*arena*/) {
  out.node_name = c_string(in.node_name);
  view_sequence(out.motor_ids, in.motor_ids);
  out.control_mode = enum_to_c(in.control_mode);
  out.default_behavior = enum_to_c(in.default_behavior);
  out.timeout_ms = in.timeout_ms;
  view_sequence(out.default_kp, in.default_kp);
  view_sequence(out.default_kd, in.default_kd);
  out.device = c_string(in.device);
  out.policy_name = c_string(in.policy_name);
  out.policy_file_name = c_string(in.policy_file_name);
  out.min_command_success_rate = in.min_command_success_rate;
  out.on_low_success_rate = enum_to_c(in.on_low_success_rate);
}
RequestControlRequest Wire<RequestControlRequest>::from_c(const C& in) {
  RequestControlRequest out;
  out.node_name = copy_string(in.node_name);
  out.motor_ids = copy_sequence<std::int32_t>(in.motor_ids);
  out.control_mode = enum_from_c<ControlMode>(in.control_mode);
  out.default_behavior = enum_from_c<Behavior>(in.default_behavior);
  out.timeout_ms = in.timeout_ms;
  out.default_kp = copy_sequence<float>(in.default_kp);
  out.default_kd = copy_sequence<float>(in.default_kd);
  out.device = copy_string(in.device);
  out.policy_name = copy_string(in.policy_name);
  out.policy_file_name = copy_string(in.policy_file_name);
  out.min_command_success_rate = in.min_command_success_rate;
  out.on_low_success_rate = enum_from_c<LowRateAction>(in.on_low_success_rate);
  return out;
}

const dds_topic_descriptor_t& Wire<RequestControlResponse>::descriptor() {
  return robotd_msgs_srv_dds__RequestControl_Response__desc;
}
void Wire<RequestControlResponse>::to_c(const RequestControlResponse& in, C& out, CArena& /*arena*/) {
  out.success = in.success;
  out.message = c_string(in.message);
  out.uuid = c_string(in.uuid);
  view_sequence(out.motor_ids, in.motor_ids);
  out.applied_behavior = enum_to_c(in.applied_behavior);
  out.device = c_string(in.device);
  out.session_id = c_string(in.session_id);
}
RequestControlResponse Wire<RequestControlResponse>::from_c(const C& in) {
  return RequestControlResponse{in.success,
                                copy_string(in.message),
                                copy_string(in.uuid),
                                copy_sequence<std::int32_t>(in.motor_ids),
                                enum_from_c<Behavior>(in.applied_behavior),
                                copy_string(in.device),
                                copy_string(in.session_id)};
}

const dds_topic_descriptor_t& Wire<ReleaseControlRequest>::descriptor() {
  return robotd_msgs_srv_dds__ReleaseControl_Request__desc;
}
void Wire<ReleaseControlRequest>::to_c(const ReleaseControlRequest& in, C& out, CArena& /*arena*/) {
  out.node_name = c_string(in.node_name);
  out.uuid = c_string(in.uuid);
  out.release_mode = enum_to_c(in.release_mode);
}
ReleaseControlRequest Wire<ReleaseControlRequest>::from_c(const C& in) {
  return ReleaseControlRequest{copy_string(in.node_name), copy_string(in.uuid), enum_from_c<Behavior>(in.release_mode)};
}

const dds_topic_descriptor_t& Wire<ReleaseControlResponse>::descriptor() {
  return robotd_msgs_srv_dds__ReleaseControl_Response__desc;
}
void Wire<ReleaseControlResponse>::to_c(const ReleaseControlResponse& in, C& out, CArena& /*arena*/) {
  out.success = in.success;
  out.message = c_string(in.message);
  out.applied_behavior = enum_to_c(in.applied_behavior);
}
ReleaseControlResponse Wire<ReleaseControlResponse>::from_c(const C& in) {
  return ReleaseControlResponse{in.success, copy_string(in.message), enum_from_c<Behavior>(in.applied_behavior)};
}

const dds_topic_descriptor_t& Wire<GetAvailableMotorsRequest>::descriptor() {
  return robotd_msgs_srv_dds__GetAvailableMotors_Request__desc;
}
void Wire<GetAvailableMotorsRequest>::to_c(const GetAvailableMotorsRequest& in, C& out, CArena& /*arena*/) {
  out.node_name = c_string(in.node_name);
  out.device = c_string(in.device);
}
GetAvailableMotorsRequest Wire<GetAvailableMotorsRequest>::from_c(const C& in) {
  return GetAvailableMotorsRequest{copy_string(in.node_name), copy_string(in.device)};
}

const dds_topic_descriptor_t& Wire<GetAvailableMotorsResponse>::descriptor() {
  return robotd_msgs_srv_dds__GetAvailableMotors_Response__desc;
}
void Wire<GetAvailableMotorsResponse>::to_c(const GetAvailableMotorsResponse& in, C& out, CArena& arena) {
  view_sequence(out.motor_ids, in.motor_ids);
  view_string_sequence(out.motor_names, in.motor_names, arena);
  out.success = in.success;
  out.message = c_string(in.message);
}
GetAvailableMotorsResponse Wire<GetAvailableMotorsResponse>::from_c(const C& in) {
  return GetAvailableMotorsResponse{copy_sequence<std::int32_t>(in.motor_ids), copy_string_sequence(in.motor_names),
                                    in.success, copy_string(in.message)};
}

const dds_topic_descriptor_t& Wire<ResetZeroRequest>::descriptor() {
  return robotd_msgs_srv_dds__ResetZero_Request__desc;
}
void Wire<ResetZeroRequest>::to_c(const ResetZeroRequest& in, C& out, CArena& /*arena*/) {
  out.device = c_string(in.device);
  view_sequence(out.motor_ids, in.motor_ids);
  out.timeout_ms = in.timeout_ms;
}
ResetZeroRequest Wire<ResetZeroRequest>::from_c(const C& in) {
  return ResetZeroRequest{copy_string(in.device), copy_sequence<std::int32_t>(in.motor_ids), in.timeout_ms};
}

const dds_topic_descriptor_t& Wire<ResetZeroResponse>::descriptor() {
  return robotd_msgs_srv_dds__ResetZero_Response__desc;
}
void Wire<ResetZeroResponse>::to_c(const ResetZeroResponse& in, C& out, CArena& /*arena*/) {
  out.success = in.success;
  out.message = c_string(in.message);
}
ResetZeroResponse Wire<ResetZeroResponse>::from_c(const C& in) {
  return ResetZeroResponse{in.success, copy_string(in.message)};
}

const dds_topic_descriptor_t& Wire<EstopRequest>::descriptor() { return robotd_msgs_srv_dds__Estop_Request__desc; }
void Wire<EstopRequest>::to_c(const EstopRequest& in, C& out, CArena& /*arena*/) {
  out.node_name = c_string(in.node_name);
  out.device = c_string(in.device);
  out.engage = in.engage;
  out.reason = c_string(in.reason);
}
EstopRequest Wire<EstopRequest>::from_c(const C& in) {
  return EstopRequest{copy_string(in.node_name), copy_string(in.device), in.engage, copy_string(in.reason)};
}

const dds_topic_descriptor_t& Wire<EstopResponse>::descriptor() { return robotd_msgs_srv_dds__Estop_Response__desc; }
void Wire<EstopResponse>::to_c(const EstopResponse& in, C& out, CArena& /*arena*/) {
  out.success = in.success;
  out.message = c_string(in.message);
}
EstopResponse Wire<EstopResponse>::from_c(const C& in) { return EstopResponse{in.success, copy_string(in.message)}; }

const dds_topic_descriptor_t& Wire<ListDevicesRequest>::descriptor() {
  return robotd_msgs_srv_dds__ListDevices_Request__desc;
}
void Wire<ListDevicesRequest>::to_c(const ListDevicesRequest& in, C& out, CArena& /*arena*/) {
  out.node_name = c_string(in.node_name);
}
ListDevicesRequest Wire<ListDevicesRequest>::from_c(const C& in) {
  return ListDevicesRequest{copy_string(in.node_name)};
}

const dds_topic_descriptor_t& Wire<ListDevicesResponse>::descriptor() {
  return robotd_msgs_srv_dds__ListDevices_Response__desc;
}
void Wire<ListDevicesResponse>::to_c(const ListDevicesResponse& in, C& out, CArena& arena) {
  auto* devices = arena.array<robotd_msgs_msg_dds__DeviceInfo_>(in.devices.size());
  for (std::size_t i = 0; i < in.devices.size(); ++i) device_info_to_c(in.devices[i], devices[i], arena);
  out.devices._length = out.devices._maximum = static_cast<std::uint32_t>(in.devices.size());
  out.devices._buffer = devices;
  out.devices._release = false;
}
ListDevicesResponse Wire<ListDevicesResponse>::from_c(const C& in) {
  ListDevicesResponse out;
  for (std::uint32_t i = 0; i < in.devices._length; ++i)
    out.devices.push_back(device_info_from_c(in.devices._buffer[i]));
  return out;
}

const dds_topic_descriptor_t& Wire<DeviceCallRequest>::descriptor() {
  return robotd_msgs_srv_dds__DeviceCall_Request__desc;
}
void Wire<DeviceCallRequest>::to_c(const DeviceCallRequest& in, C& out, CArena& /*arena*/) {
  out.device = c_string(in.device);
  out.op = c_string(in.op);
  out.args_json = c_string(in.args_json);
}
DeviceCallRequest Wire<DeviceCallRequest>::from_c(const C& in) {
  return DeviceCallRequest{copy_string(in.device), copy_string(in.op), copy_string(in.args_json)};
}

const dds_topic_descriptor_t& Wire<DeviceCallResponse>::descriptor() {
  return robotd_msgs_srv_dds__DeviceCall_Response__desc;
}
void Wire<DeviceCallResponse>::to_c(const DeviceCallResponse& in, C& out, CArena& /*arena*/) {
  out.success = in.success;
  out.message = c_string(in.message);
  out.result_json = c_string(in.result_json);
}
DeviceCallResponse Wire<DeviceCallResponse>::from_c(const C& in) {
  return DeviceCallResponse{in.success, copy_string(in.message), copy_string(in.result_json)};
}

}  // namespace robotd::wire
