#include "driver/xarm_params.hpp"

#include <sstream>
#include <vector>

#include "robotd/driver/json_reader.hpp"

namespace robotd::xarm {
namespace {

constexpr double kMaxServoRateHz = 250;  // the control box's command rate limit (§2.6)

std::string model_names() {
  std::string names;
  for (const ArmModel& model : known_models()) names += (names.empty() ? "" : ", ") + std::string(model.name);
  return names;
}

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

int report_period_ms(ReportKind kind) {
  switch (kind) {
    case ReportKind::kReal:
      return 10;
    case ReportKind::kNormal:
    case ReportKind::kRich:
      return 200;
    case ReportKind::kRealtime:
      return 4;
  }
  return 10;
}

void read_model(JsonReader& reader, XarmParams& out) {
  reader.require("model", "the arm's model: " + model_names());
  const auto name = reader.string("model");
  if (!name) return;
  const auto model = find_model(*name);
  if (!model) {
    reader.error("model", "unknown xArm model \"" + *name + "\"; expected one of " + model_names());
    return;
  }
  out.model = *model;
  for (std::size_t j = 0; j < model->dof; ++j) {
    out.limits[j] = driver::JointLimits{
        .position_min_rad = model->min_rad[j],
        .position_max_rad = model->max_rad[j],
        .velocity_max_rad_s = kMaxJointSpeedRadS,
        .acceleration_max_rad_s2 = 20.0,  // 1145 °/s², the controller's joint acceleration limit
        // Position-controlled joints: no torque commands, no gains. robotd needs positive bounds.
        .effort_max_nm = 1.0,
        .kp_max = 1.0,
        .kd_max = 1.0,
    };
  }
}

void read_joint(JsonReader& reader, driver::JointLimits& limits) {
  limits.position_min_rad = reader.number_or("position_min_rad", limits.position_min_rad);
  limits.position_max_rad = reader.number_or("position_max_rad", limits.position_max_rad);
  limits.velocity_max_rad_s = reader.number_or("velocity_max_rad_s", limits.velocity_max_rad_s,
                                               NumberRange{.min = 1e-9, .max = kMaxJointSpeedRadS});
  limits.acceleration_max_rad_s2 =
      reader.number_or("acceleration_max_rad_s2", limits.acceleration_max_rad_s2, NumberRange{.min = 1e-9});
  if (!(limits.position_min_rad < limits.position_max_rad)) {
    reader.error("position_min_rad", "expected less than position_max_rad (" + format_number(limits.position_max_rad) +
                                         "), got " + format_number(limits.position_min_rad));
  }
  reader.finish();
}

void read_joints(JsonReader& reader, XarmParams& out) {
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
}

void read_report(JsonReader& reader, XarmParams& out) {
  const std::string kind = reader.string_or("kind", "real", {"real", "realtime", "normal"});
  out.report_kind = parse_report_kind(kind).value_or(ReportKind::kReal);
  out.report_port = default_report_port(out.report_kind);
  out.report_port = static_cast<std::uint16_t>(reader.integer_or("port", out.report_port, 1, 65535));
  out.report_timeout_ms = std::max(out.report_timeout_ms, 3 * report_period_ms(out.report_kind));
  out.report_timeout_ms = static_cast<int>(reader.integer_or("timeout_ms", out.report_timeout_ms, 10, 10'000));
  if (out.report_timeout_ms < 2 * report_period_ms(out.report_kind)) {
    reader.error("timeout_ms", "expected at least two report periods (" +
                                   std::to_string(2 * report_period_ms(out.report_kind)) + " ms for the " + kind +
                                   " report), got " + std::to_string(out.report_timeout_ms));
  }
  reader.finish();
}

}  // namespace

Result<XarmParams> parse_xarm_params(const nlohmann::json& params) {
  std::vector<std::string> errors;
  JsonReader reader(params, "", errors);
  XarmParams out;
  read_model(reader, out);
  out.controller.host = reader.string_or("host", out.controller.host);
  out.controller.port = static_cast<std::uint16_t>(reader.integer_or("port", out.controller.port, 1, 65535));
  if (auto report = reader.object("report")) read_report(*report, out);
  out.connect_timeout_ms =
      static_cast<int>(reader.integer_or("connect_timeout_ms", out.connect_timeout_ms, 10, 60'000));
  out.request_timeout_ms =
      static_cast<int>(reader.integer_or("request_timeout_ms", out.request_timeout_ms, 10, 60'000));
  out.servo_rate_hz =
      reader.number_or("servo_rate_hz", out.servo_rate_hz, NumberRange{.min = 1, .max = kMaxServoRateHz});
  const std::string enable = reader.string_or("enable", "on_session", {"on_session", "on_connect", "manual"});
  out.enable = enable == "on_connect" ? EnablePolicy::kOnConnect
               : enable == "manual"   ? EnablePolicy::kManual
                                      : EnablePolicy::kOnSession;
  out.error_poll_ms = static_cast<int>(reader.integer_or("error_poll_ms", out.error_poll_ms, 10, 10'000));
  out.io_priority = static_cast<int>(reader.integer_or("io_priority", out.io_priority, 0, 98));
  read_joints(reader, out);
  reader.finish();
  if (!errors.empty()) return make_error(ErrorCode::kInvalidArgument, join_errors(errors));
  return out;
}

}  // namespace robotd::xarm
