#include "message_json.hpp"

#include <cmath>
#include <string>

namespace robotctl {
namespace {

// Timing statistics are floats; rounding to the nanosecond keeps "12.3", not "12.300000190734863".
double microseconds(float value_us) { return std::round(static_cast<double>(value_us) * 1000.0) / 1000.0; }

Json to_json(const robotd::Time& time) { return Json{{"sec", time.sec}, {"nanosec", time.nanosec}}; }

Json to_json(const robotd::Header& header) {
  return Json{{"stamp", to_json(header.stamp)}, {"frame_id", header.frame_id}};
}

Json to_json(const robotd::Vector3& v) { return Json{{"x", v.x}, {"y", v.y}, {"z", v.z}}; }

Json to_json(const robotd::LoopStatistics& loop) {
  return Json{{"rate_hz", loop.rate_hz},
              {"realtime", loop.realtime},
              {"ticks", loop.ticks},
              {"overruns", loop.overruns},
              {"window_ticks", loop.window_ticks},
              {"period_p50_us", microseconds(loop.period_p50_us)},
              {"period_p99_us", microseconds(loop.period_p99_us)},
              {"period_max_us", microseconds(loop.period_max_us)},
              {"wake_latency_p50_us", microseconds(loop.wake_latency_p50_us)},
              {"wake_latency_p99_us", microseconds(loop.wake_latency_p99_us)},
              {"wake_latency_max_us", microseconds(loop.wake_latency_max_us)},
              {"execution_p50_us", microseconds(loop.execution_p50_us)},
              {"execution_p99_us", microseconds(loop.execution_p99_us)},
              {"execution_max_us", microseconds(loop.execution_max_us)},
              {"rt_heap_allocations", loop.rt_heap_allocations},
              {"tick_deadline_steady_ns", loop.tick_deadline_steady_ns},
              {"period_ns", loop.period_ns}};
}

Json to_json(const robotd::CommandCounters& commands) {
  return Json{{"received", commands.received},
              {"accepted", commands.accepted},
              {"clamped", commands.clamped},
              {"rejected_unknown_session", commands.rejected_unknown_session},
              {"rejected_wrong_device", commands.rejected_wrong_device},
              {"rejected_not_owner", commands.rejected_not_owner},
              {"rejected_unknown_motor", commands.rejected_unknown_motor},
              {"rejected_malformed", commands.rejected_malformed},
              {"rejected_non_finite", commands.rejected_non_finite},
              {"rejected_out_of_range", commands.rejected_out_of_range},
              {"rejected_estop", commands.rejected_estop},
              {"rejected_fault", commands.rejected_fault},
              {"dropped_stale", commands.dropped_stale}};
}

Json to_json(const robotd::SessionInfo& session) {
  return Json{{"uuid", session.uuid},
              {"node_name", session.node_name},
              {"device", session.device},
              {"motor_ids", session.motor_ids},
              {"control_mode", robotd::to_string(session.control_mode)},
              {"default_behavior", robotd::to_string(session.default_behavior)},
              {"applied_behavior", robotd::to_string(session.applied_behavior)},
              {"timeout_ms", session.timeout_ms},
              {"time_left_ms", session.time_left_ms},
              {"granted_at", to_json(session.granted_at)},
              {"commands_accepted", session.commands_accepted},
              {"policy_name", session.policy_name},
              {"policy_file_name", session.policy_file_name},
              {"closed_loop", session.closed_loop},
              {"ticks_to_answer", session.ticks_to_answer},
              {"ticks_answered_in_time", session.ticks_answered_in_time},
              {"ticks_answered_late", session.ticks_answered_late},
              {"ticks_unanswered", session.ticks_unanswered},
              {"command_success_rate", session.command_success_rate},
              {"min_command_success_rate", session.min_command_success_rate},
              {"on_low_success_rate", robotd::to_string(session.on_low_success_rate)},
              {"success_rate_low", session.success_rate_low}};
}

Json to_json(const robotd::SurfaceCounters& surface) {
  Json services = Json::array();
  for (const auto& service : surface.services) {
    services.push_back(Json{{"service", service.service},
                            {"requests", service.requests},
                            {"refused", service.refused},
                            {"oversized", service.oversized}});
  }
  return Json{{"commands_unattributed", surface.commands_unattributed},
              {"dds_log_messages", surface.dds_log_messages},
              {"services", services}};
}

}  // namespace

Json to_json(const std::vector<robotd::DeviceInfo>& devices) {
  Json list = Json::array();
  for (const auto& device : devices) list.push_back(to_json(device));
  return list;
}

Json to_json(const robotd::DeviceInfo& device) {
  Json behavior_map = Json::array();
  for (const auto behavior : device.behavior_map) {
    behavior_map.push_back(robotd::to_string(static_cast<robotd::Behavior>(behavior)));
  }
  return Json{{"name", device.name},
              {"driver", device.driver},
              {"driver_version", device.driver_version},
              {"model", device.model},
              {"kinematic_model", device.kinematic_model},
              {"rate_hz", device.rate_hz},
              {"native_rate_hz", device.native_rate_hz},
              {"joint_names", device.joint_names},
              {"position_min", device.position_min},
              {"position_max", device.position_max},
              {"velocity_max", device.velocity_max},
              {"acceleration_max", device.acceleration_max},
              {"effort_max", device.effort_max},
              {"control_modes", device.control_modes},
              {"behavior_map", behavior_map},
              {"ops", device.ops},
              {"state", robotd::to_string(device.state)}};
}

Json to_json(const robotd::DeviceStatus& status) {
  Json driver_values = Json::object();
  for (const auto& value : status.driver_values) driver_values[value.key] = value.value;
  return Json{{"header", to_json(status.header)}, {"device", status.device},
              {"driver", status.driver},          {"state", robotd::to_string(status.state)},
              {"state_text", status.state_text},  {"fault_code", status.fault_code},
              {"fault_text", status.fault_text},  {"estop_engaged", status.estop_engaged},
              {"loop", to_json(status.loop)},     {"commands", to_json(status.commands)},
              {"driver_values", driver_values}};
}

Json to_json(const robotd::SessionStatus& status) {
  Json sessions = Json::array();
  for (const auto& session : status.sessions) sessions.push_back(to_json(session));
  return Json{{"header", to_json(status.header)},    {"state", status.state},
              {"policy_name", status.policy_name},   {"policy_file_name", status.policy_file_name},
              {"active_uuids", status.active_uuids}, {"node_names", status.node_names},
              {"motor_counts", status.motor_counts}, {"sessions", sessions},
              {"surface", to_json(status.surface)}};
}

Json to_json(const robotd::JointState& state) {
  return Json{{"header", to_json(state.header)},
              {"name", state.name},
              {"position", state.position},
              {"velocity", state.velocity},
              {"effort", state.effort}};
}

Json to_json(const robotd::Imu& imu) {
  const robotd::Quaternion& q = imu.orientation;
  return Json{{"header", to_json(imu.header)},
              {"orientation", Json{{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}}},
              {"angular_velocity", to_json(imu.angular_velocity)},
              {"linear_acceleration", to_json(imu.linear_acceleration)}};
}

Json to_json(const robotd::PoseStamped& pose) {
  const robotd::Quaternion& q = pose.orientation;
  return Json{{"header", to_json(pose.header)},
              {"position", to_json(pose.position)},
              {"orientation", Json{{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}}}};
}

Json to_json(const robotd::Joy& joy) {
  // Message order, header last as in the PI Plus message.
  return Json{{"l_horizontal", joy.l_horizontal},
              {"l_vertical", joy.l_vertical},
              {"lt", joy.lt},
              {"r_horizontal", joy.r_horizontal},
              {"r_vertical", joy.r_vertical},
              {"rt", joy.rt},
              {"dpad_horizontal", joy.dpad_horizontal},
              {"dpad_vertical", joy.dpad_vertical},
              {"a", joy.a},
              {"b", joy.b},
              {"x", joy.x},
              {"y", joy.y},
              {"lb", joy.lb},
              {"rb", joy.rb},
              {"back", joy.back},
              {"start", joy.start},
              {"center", joy.center},
              {"l", joy.l},
              {"r", joy.r},
              {"header", to_json(joy.header)}};
}

Json to_json(const robotd::PolicyData& data) {
  return Json{{"header", to_json(data.header)}, {"data_type", data.data_type}, {"data", data.data}};
}

std::string compact_text(const Json& json) { return json.dump(-1, ' ', false, Json::error_handler_t::replace); }

std::string pretty_text(const Json& json) { return json.dump(2, ' ', false, Json::error_handler_t::replace); }

}  // namespace robotctl
