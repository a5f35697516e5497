#include "driver/realman_params.hpp"

#include <sstream>
#include <vector>

#include "robotd/driver/json_reader.hpp"

namespace robotd::realman {
namespace {

constexpr double kHighFollowMinRateHz = 100;  // high follow needs a period of at most 10 ms (§3.3)

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string model_names() {
  std::string names;
  for (const ArmModel& model : known_models()) names += (names.empty() ? "" : ", ") + std::string(model.name);
  return names;
}

void read_model(JsonReader& reader, RealmanParams& out) {
  const std::string name = reader.string_or("model", "RM65");
  const auto model = find_model(name);
  if (!model) {
    reader.error("model", "unknown RealMan model \"" + name + "\"; expected one of " + model_names());
    return;
  }
  out.model = *model;
  for (std::size_t j = 0; j < model->dof; ++j) {
    out.limits[j] = driver::JointLimits{
        .position_min_rad = model->min_rad[j],
        .position_max_rad = model->max_rad[j],
        .velocity_max_rad_s = kPassThroughMaxSpeedRadS,  // what pass-through accepts
        .acceleration_max_rad_s2 = 5.0,
        // Position-controlled joints: no torque, no gains. robotd needs positive bounds.
        .effort_max_nm = 1.0,
        .kp_max = 1.0,
        .kd_max = 1.0,
    };
  }
}

void read_joint(JsonReader& reader, driver::JointLimits& limits) {
  const NumberRange positive{.min = 1e-9};
  limits.position_min_rad = reader.number_or("position_min_rad", limits.position_min_rad);
  limits.position_max_rad = reader.number_or("position_max_rad", limits.position_max_rad);
  limits.velocity_max_rad_s = reader.number_or("velocity_max_rad_s", limits.velocity_max_rad_s,
                                               NumberRange{.min = 1e-9, .max = kPassThroughMaxSpeedRadS});
  limits.acceleration_max_rad_s2 =
      reader.number_or("acceleration_max_rad_s2", limits.acceleration_max_rad_s2, positive);
  if (!(limits.position_min_rad < limits.position_max_rad)) {
    reader.error("position_min_rad", "expected less than position_max_rad (" + format_number(limits.position_max_rad) +
                                         "), got " + format_number(limits.position_min_rad));
  }
  reader.finish();
}

void read_pass_through(JsonReader& reader, RealmanParams& out) {
  out.pass_through.follow = reader.boolean_or("follow", out.pass_through.follow);
  if (reader.has("trajectory_mode")) {
    out.pass_through.trajectory_mode = static_cast<int>(reader.integer_or("trajectory_mode", 0, 0, 2));
  }
  if (reader.has("radio")) {
    const int max_radio = out.pass_through.trajectory_mode == 1 ? 100 : 1000;
    out.pass_through.radio = static_cast<int>(reader.integer_or("radio", 0, 0, max_radio));
    if (!out.pass_through.trajectory_mode) {
      reader.error("radio", "only applies with trajectory_mode 1 (curve fitting) or 2 (filter); set trajectory_mode");
    }
  }
  if (out.pass_through.trajectory_mode && !out.pass_through.follow) {
    reader.error("trajectory_mode", "only applies in high follow; set follow: true or drop trajectory_mode");
  }
}

void read_push(JsonReader& reader, PushParams& push) {
  push.enabled = reader.boolean_or("enabled", push.enabled);
  push.port = static_cast<std::uint16_t>(reader.integer_or("port", push.port, 0, 65535));
  push.ip = reader.string_or("ip", push.ip);
  push.cycle = static_cast<int>(reader.integer_or("cycle", push.cycle, 1, 200));
  push.joint_speed = reader.boolean_or("joint_speed", push.joint_speed);
  const std::string unit = reader.string_or("speed_unit", "0.01deg/s", {"0.01deg/s", "0.01rpm", "0.02deg/s"});
  push.speed_unit = unit == "0.01rpm"     ? SpeedUnit::kCentiRpm
                    : unit == "0.02deg/s" ? SpeedUnit::kFiftiethDegreesPerSecond
                                          : SpeedUnit::kCentiDegreesPerSecond;
  reader.finish();
}

}  // namespace

Result<RealmanParams> parse_realman_params(const nlohmann::json& params) {
  std::vector<std::string> errors;
  JsonReader reader(params, "", errors);
  RealmanParams out;
  read_model(reader, out);
  out.controller.host = reader.string_or("host", out.controller.host);
  out.controller.port = static_cast<std::uint16_t>(reader.integer_or("port", out.controller.port, 1, 65535));
  out.connect_timeout_ms =
      static_cast<int>(reader.integer_or("connect_timeout_ms", out.connect_timeout_ms, 10, 60'000));
  out.request_timeout_ms =
      static_cast<int>(reader.integer_or("request_timeout_ms", out.request_timeout_ms, 10, 60'000));
  out.command_rate_hz = reader.number_or("command_rate_hz", out.command_rate_hz, NumberRange{.min = 1, .max = 500});
  read_pass_through(reader, out);
  if (out.pass_through.follow && out.command_rate_hz < kHighFollowMinRateHz) {
    reader.error("command_rate_hz",
                 "high follow (follow: true) needs a period of at most 10 ms, i.e. at least 100 Hz; "
                 "got " +
                     format_number(out.command_rate_hz) + " (or set follow: false)");
  }
  if (auto push = reader.object("push")) read_push(*push, out.push);
  out.poll_period_ms = static_cast<int>(reader.integer_or("poll_period_ms", out.poll_period_ms, 5, 1000));
  out.feedback_timeout_ms =
      static_cast<int>(reader.integer_or("feedback_timeout_ms", out.feedback_timeout_ms, 20, 10'000));
  out.io_priority = static_cast<int>(reader.integer_or("io_priority", out.io_priority, 0, 98));
  for (auto& [name, joint_reader] : reader.object_map("joints")) {
    bool found = false;
    for (std::size_t j = 0; j < out.model.dof; ++j) {
      if (name == "joint" + std::to_string(j + 1)) {
        read_joint(joint_reader, out.limits[j]);
        found = true;
      }
    }
    if (!found) {
      reader.error("joints", "unknown joint \"" + name + "\"; expected joint1 … joint" + std::to_string(out.model.dof));
    }
  }
  reader.finish();
  const int feedback_period_ms = out.push.enabled ? 5 * out.push.cycle : out.poll_period_ms;
  if (out.feedback_timeout_ms < 2 * feedback_period_ms) {
    errors.push_back("feedback_timeout_ms: expected at least two feedback periods (" +
                     std::to_string(2 * feedback_period_ms) + " ms with " +
                     (out.push.enabled ? "push.cycle " + std::to_string(out.push.cycle)
                                       : "poll_period_ms " + std::to_string(out.poll_period_ms)) +
                     "), got " + std::to_string(out.feedback_timeout_ms));
  }
  if (!errors.empty()) return make_error(ErrorCode::kInvalidArgument, join_errors(errors));
  return out;
}

}  // namespace robotd::realman
