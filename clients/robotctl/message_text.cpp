#include "message_text.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <utility>

#include "text_format.hpp"
#include "text_table.hpp"

namespace robotctl {
namespace {

// "+0.5000" / "-0.5000"; a value that rounds to zero prints as "+0.0000", never "-0.0000".
std::string signed_fixed(double value, int decimals) {
  const std::string text = fixed(value, decimals);
  if (text.front() != '-') return "+" + text;
  return text.find_first_not_of("-0.") == std::string::npos ? "+" + text.substr(1) : text;
}

std::string vector_text(const robotd::Vector3& v) {
  return "x " + signed_fixed(v.x, 4) + "  y " + signed_fixed(v.y, 4) + "  z " + signed_fixed(v.z, 4);
}

std::string labelled(const std::string& label, const std::string& value) {
  std::string line = "  " + label;
  line.append(label.size() < 13 ? 13 - label.size() : 1, ' ');
  return line + value + "\n";
}

// "p50 12.3  p99 45.6  max 120.0 µs".
std::string percentiles_text(float p50_us, float p99_us, float max_us) {
  return "p50 " + fixed(p50_us, 1) + "  p99 " + fixed(p99_us, 1) + "  max " + fixed(max_us, 1) + " µs";
}

// The rejection counters that are not zero, by reason ("not_owner", ...).
std::vector<std::pair<std::string, std::uint64_t>> nonzero_rejections(const robotd::CommandCounters& counters) {
  const std::vector<std::pair<std::string, std::uint64_t>> all = {
      {"unknown_session", counters.rejected_unknown_session},
      {"wrong_device", counters.rejected_wrong_device},
      {"not_owner", counters.rejected_not_owner},
      {"unknown_motor", counters.rejected_unknown_motor},
      {"malformed", counters.rejected_malformed},
      {"non_finite", counters.rejected_non_finite},
      {"out_of_range", counters.rejected_out_of_range},
      {"estop", counters.rejected_estop},
      {"fault", counters.rejected_fault},
  };
  std::vector<std::pair<std::string, std::uint64_t>> nonzero;
  for (const auto& entry : all) {
    if (entry.second > 0) nonzero.push_back(entry);
  }
  return nonzero;
}

}  // namespace

std::string device_table(const std::vector<robotd::DeviceInfo>& devices) {
  TextTable table({"NAME", "DRIVER", "MODEL", "KINEMATIC MODEL", "JOINTS", "RATE Hz", "CONTROL MODES", "STATE"});
  for (const auto& device : devices) {
    table.add_row({device.name, device.driver + (device.driver_version.empty() ? "" : " " + device.driver_version),
                   device.model, device.kinematic_model.empty() ? "-" : device.kinematic_model,
                   std::to_string(device.joint_names.size()), fixed(device.rate_hz, 0), join(device.control_modes, ","),
                   std::string(robotd::to_string(device.state))});
  }
  return table.render();
}

std::string state_text(const robotd::DeviceStatus& status) {
  std::string name(robotd::to_string(status.state));
  if (status.state_text.empty() || status.state_text == name) return name;
  if (status.state_text.rfind(name, 0) == 0) return status.state_text;
  return name + " — " + status.state_text;
}

std::string device_status_text(const robotd::DeviceStatus& status) {
  const robotd::LoopStatistics& loop = status.loop;
  std::string text = status.device + "  " + state_text(status) + "\n";
  std::vector<std::string> driver_values;
  driver_values.reserve(status.driver_values.size());
  for (const auto& value : status.driver_values) driver_values.push_back(value.key + "=" + value.value);
  text += labelled("driver", status.driver + (driver_values.empty() ? "" : ": " + join(driver_values, " ")));
  text += labelled("fault", status.fault_code == 0 && status.fault_text.empty()
                                ? "none"
                                : "code " + std::to_string(status.fault_code) + ": " + status.fault_text);
  text += labelled("e-stop", status.estop_engaged ? "engaged" : "clear");
  text += labelled("loop", fixed(loop.rate_hz, 0) + " Hz, realtime " + yes_no(loop.realtime) + ", " +
                               std::to_string(loop.ticks) + " ticks, " + std::to_string(loop.overruns) +
                               " overruns (timing over the last " + std::to_string(loop.window_ticks) + " ticks)");
  text +=
      labelled("wake", percentiles_text(loop.wake_latency_p50_us, loop.wake_latency_p99_us, loop.wake_latency_max_us));
  text += labelled("execution", percentiles_text(loop.execution_p50_us, loop.execution_p99_us, loop.execution_max_us));
  text += labelled("period", "p50 " + fixed(loop.period_p50_us, 1) + "  p99 " + fixed(loop.period_p99_us, 1) + " µs");
  if (loop.rt_heap_allocations >= 0) {
    text += labelled("rt heap", std::to_string(loop.rt_heap_allocations) + " allocations in the loop");
  }
  text += labelled(
      "commands", "received " + std::to_string(status.commands.received) + ", accepted " +
                      std::to_string(status.commands.accepted) +
                      (status.commands.clamped > 0 ? ", clamped " + std::to_string(status.commands.clamped) : "") +
                      (status.commands.dropped_stale > 0
                           ? ", " + std::to_string(status.commands.dropped_stale) + " arrived after their session ended"
                           : ""));
  std::vector<std::string> rejections;
  for (const auto& [reason, count] : nonzero_rejections(status.commands)) {
    rejections.push_back(reason + " " + std::to_string(count));
  }
  if (!rejections.empty()) text += labelled("rejected", join(rejections, ", "));
  return text;
}

std::string behavior_text(robotd::Behavior requested, robotd::Behavior applied) {
  std::string text(robotd::to_string(requested));
  if (applied != requested) text += " → " + std::string(robotd::to_string(applied));
  return text;
}

namespace {

std::string policy_text(const robotd::SessionInfo& session) {
  if (session.policy_file_name.empty()) return session.policy_name.empty() ? "-" : session.policy_name;
  return (session.policy_name.empty() ? "-" : session.policy_name) + " (" + session.policy_file_name + ")";
}

// A closed-loop session's answers: "98.0 % (in time 980, late 15, never 5; min 95.0 % WARN)",
// "LOW" appended while its rate is below its minimum.
std::string answers_text(const robotd::SessionInfo& session) {
  std::string text = "-";
  if (session.closed_loop) {
    text = fixed(100.0 * session.command_success_rate, 1) + " % (in time " +
           std::to_string(session.ticks_answered_in_time) + ", late " + std::to_string(session.ticks_answered_late) +
           ", never " + std::to_string(session.ticks_unanswered);
  }
  if (session.min_command_success_rate > 0) {
    text += std::string(session.closed_loop ? "; " : " (") + "min " +
            fixed(100.0 * session.min_command_success_rate, 1) + " % " +
            std::string(robotd::to_string(session.on_low_success_rate));
  }
  if (session.closed_loop || session.min_command_success_rate > 0) text += ")";
  if (session.success_rate_low) text += " LOW";
  return text;
}

}  // namespace

std::string session_table(const robotd::SessionStatus& status) {
  if (status.sessions.empty()) return "no active sessions\n";
  // The POLICY column only when a session named one (most clients do not).
  const bool policies = std::any_of(status.sessions.begin(), status.sessions.end(), [](const auto& session) {
    return !session.policy_name.empty() || !session.policy_file_name.empty();
  });
  // The ANSWERS column (command success rate) only when a session closes the loop or asked for a minimum.
  const bool closed_loop = std::any_of(status.sessions.begin(), status.sessions.end(), [](const auto& session) {
    return session.closed_loop || session.min_command_success_rate > 0;
  });
  std::vector<std::string> headers{"SESSION", "NODE",       "DEVICE",    "MOTORS",
                                   "MODE",    "ON TIMEOUT", "TIME LEFT", "COMMANDS"};
  if (closed_loop) headers.emplace_back("ANSWERS IN TIME");
  if (policies) headers.emplace_back("POLICY");
  TextTable table(std::move(headers));
  for (const auto& session : status.sessions) {
    std::vector<std::string> row{session.uuid,
                                 session.node_name,
                                 session.device,
                                 id_ranges(session.motor_ids),
                                 std::string(robotd::to_string(session.control_mode)),
                                 behavior_text(session.default_behavior, session.applied_behavior),
                                 std::to_string(session.time_left_ms) + " ms",
                                 std::to_string(session.commands_accepted)};
    if (closed_loop) row.push_back(answers_text(session));
    if (policies) row.push_back(policy_text(session));
    table.add_row(std::move(row));
  }
  return table.render();
}

std::string surface_text(const robotd::SurfaceCounters& surface) {
  std::vector<std::string> services;
  services.reserve(surface.services.size());
  for (const auto& service : surface.services) {
    std::string entry = service.service + " " + std::to_string(service.requests);
    if (service.refused > 0 || service.oversized > 0) {
      entry += " (" + std::to_string(service.refused) + " refused" +
               (service.oversized > 0 ? ", " + std::to_string(service.oversized) + " oversized" : "") + ")";
    }
    services.push_back(entry);
  }
  return "dds surface\n" +
         labelled("commands", std::to_string(surface.commands_unattributed) +
                                  " commands named no active session and no known device") +
         labelled("requests", services.empty() ? "none" : join(services, ", ")) +
         labelled("dds layer",
                  std::to_string(surface.dds_log_messages) + " warnings and errors (robotd's log shows them)");
}

std::string joint_state_text(const robotd::JointState& state) {
  TextTable table({"  JOINT", "POSITION rad", "VELOCITY rad/s", "EFFORT N·m"});
  for (std::size_t j = 0; j < state.name.size(); ++j) {
    const auto value = [j](const std::vector<double>& values, int decimals) {
      return j < values.size() ? signed_fixed(values[j], decimals) : "-";
    };
    table.add_row({"  " + state.name[j], value(state.position, 4), value(state.velocity, 4), value(state.effort, 3)});
  }
  return state.header.frame_id + "  stamp " + stamp_text(state.header.stamp) + "\n" + table.render();
}

std::string end_pose_text(const robotd::PoseStamped& pose) {
  const robotd::Quaternion& q = pose.orientation;
  return pose.header.frame_id + "  stamp " + stamp_text(pose.header.stamp) + "\n" +
         labelled("position", vector_text(pose.position) + " m") +
         labelled("orientation", "x " + signed_fixed(q.x, 4) + "  y " + signed_fixed(q.y, 4) + "  z " +
                                     signed_fixed(q.z, 4) + "  w " + signed_fixed(q.w, 4));
}

std::string imu_text(const robotd::Imu& imu) {
  const robotd::Quaternion& q = imu.orientation;
  return imu.header.frame_id + "  stamp " + stamp_text(imu.header.stamp) + "\n" +
         labelled("orientation", "x " + signed_fixed(q.x, 4) + "  y " + signed_fixed(q.y, 4) + "  z " +
                                     signed_fixed(q.z, 4) + "  w " + signed_fixed(q.w, 4)) +
         labelled("angular", vector_text(imu.angular_velocity) + " rad/s") +
         labelled("linear", vector_text(imu.linear_acceleration) + " m/s²");
}

std::string joy_text(const robotd::Joy& joy) {
  const auto stick = [](float horizontal, float vertical) {
    return "h " + signed_fixed(horizontal, 3) + "  v " + signed_fixed(vertical, 3);
  };
  const std::vector<std::pair<std::string, float>> buttons = {
      {"A", joy.a},       {"B", joy.b},         {"X", joy.x},           {"Y", joy.y},  {"LB", joy.lb}, {"RB", joy.rb},
      {"back", joy.back}, {"start", joy.start}, {"center", joy.center}, {"L3", joy.l}, {"R3", joy.r}};
  std::vector<std::string> held;
  for (const auto& [name, value] : buttons) {
    if (value != 0.0F) held.push_back(name);
  }
  return joy.header.frame_id + "  stamp " + stamp_text(joy.header.stamp) + "\n" +
         labelled("left stick", stick(joy.l_horizontal, joy.l_vertical)) +
         labelled("right stick", stick(joy.r_horizontal, joy.r_vertical)) +
         labelled("triggers", "lt " + fixed(joy.lt, 3) + "  rt " + fixed(joy.rt, 3)) +
         labelled("d-pad", stick(joy.dpad_horizontal, joy.dpad_vertical)) +
         labelled("buttons", held.empty() ? "none" : join(held, " "));
}

std::string policy_data_text(const robotd::PolicyData& data) {
  std::vector<std::string> values;
  values.reserve(data.data.size());
  for (const double value : data.data) {
    std::array<char, 32> text{};
    std::snprintf(text.data(), text.size(), "%.6g", value);
    values.emplace_back(text.data());
  }
  return "policy_data  " + data.data_type + "  stamp " + stamp_text(data.header.stamp) + "\n" +
         labelled("data",
                  std::to_string(data.data.size()) + " values" + (values.empty() ? "" : ": " + join(values, " ")));
}

}  // namespace robotctl
