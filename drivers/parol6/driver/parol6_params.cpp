#include "driver/parol6_params.hpp"

#include <sstream>
#include <vector>

#include "driver/gripper_current.hpp"
#include "robotd/driver/json_reader.hpp"

namespace robotd::parol6 {
namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

driver::JointLimits spec_limits(int joint) {
  const JointUnits& units = joint_units()[static_cast<std::size_t>(joint)];
  return driver::JointLimits{
      .position_min_rad = units.min_rad,
      .position_max_rad = units.max_rad,
      .velocity_max_rad_s = steps_per_s_to_rad_per_s(joint, units.max_speed_steps_s),
      .acceleration_max_rad_s2 = steps_per_s_to_rad_per_s(joint, units.max_acceleration_steps_s2),
      // Steppers under position control: no torque, no gains. robotd needs positive bounds.
      .effort_max_nm = 1.0,
      .kp_max = 1.0,
      .kd_max = 1.0,
  };
}

void read_joint(JsonReader& reader, driver::JointLimits& limits) {
  const NumberRange positive{.min = 1e-9};
  limits.position_min_rad = reader.number_or("position_min_rad", limits.position_min_rad);
  limits.position_max_rad = reader.number_or("position_max_rad", limits.position_max_rad);
  limits.velocity_max_rad_s = reader.number_or("velocity_max_rad_s", limits.velocity_max_rad_s, positive);
  limits.acceleration_max_rad_s2 =
      reader.number_or("acceleration_max_rad_s2", limits.acceleration_max_rad_s2, positive);
  if (!(limits.position_min_rad < limits.position_max_rad)) {
    reader.error("position_min_rad", "expected less than position_max_rad (" + format_number(limits.position_max_rad) +
                                         "), got " + format_number(limits.position_min_rad));
  }
  reader.finish();
}

}  // namespace

Result<Parol6Params> parse_parol6_params(const nlohmann::json& params) {
  std::vector<std::string> errors;
  JsonReader reader(params, "", errors);
  Parol6Params out;
  for (int j = 0; j < kJoints; ++j) out.limits[static_cast<std::size_t>(j)] = spec_limits(j);

  out.model = reader.string_or("model", out.model);
  reader.require("serial", R"(the serial line, e.g. {"device": "/dev/ttyACM0", "baud": 3000000})");
  if (auto serial = reader.object("serial")) out.serial = transport::read_serial_link(*serial);
  out.exchange_rate_hz = reader.number_or("exchange_rate_hz", out.exchange_rate_hz, NumberRange{.min = 10, .max = 500});
  out.reply_timeout_ms = static_cast<int>(reader.integer_or("reply_timeout_ms", out.reply_timeout_ms, 20, 10000));
  out.connect_timeout_ms = static_cast<int>(reader.integer_or("connect_timeout_ms", out.connect_timeout_ms, 50, 10000));
  out.home_on_connect = reader.boolean_or("home_on_connect", out.home_on_connect);
  out.gripper_id = static_cast<int>(reader.integer_or("gripper_id", out.gripper_id, 0, 15));
  out.gripper_speed = static_cast<int>(reader.integer_or("gripper_speed", out.gripper_speed, 0, 255));
  out.gripper_current_a = reader.number_or("gripper_current_a", out.gripper_current_a,
                                           NumberRange{.min = kGripperCurrentMinA, .max = kGripperCurrentMaxA});
  for (auto& [name, joint_reader] : reader.object_map("joints")) {
    bool found = false;
    for (int j = 0; j < kJoints; ++j) {
      if (name == "joint" + std::to_string(j + 1)) {
        read_joint(joint_reader, out.limits[static_cast<std::size_t>(j)]);
        found = true;
      }
    }
    if (!found) reader.error("joints", "unknown joint \"" + name + "\"; expected joint1 … joint6");
  }
  reader.finish();
  if (!errors.empty()) return make_error(ErrorCode::kInvalidArgument, join_errors(errors));
  return out;
}

}  // namespace robotd::parol6
