// Motion state, mode, motors and brakes, error clearing, motion limits, the TCP offset and the
// stored configuration.
#include "driver/xarm_ops.hpp"

namespace robotd::xarm {

Result<nlohmann::json> XarmOps::plain(const std::string& op, Register reg, const nlohmann::json& args) {
  driver::OpArguments arguments(op, args, op_usage(op));
  if (auto error = arguments.finish()) return *error;
  return acknowledge(op, plain_request(reg));
}

Result<nlohmann::json> XarmOps::motion_en(const nlohmann::json& args) {
  driver::OpArguments arguments("motion_en", args, op_usage("motion_en"));
  const auto joint = joint_argument(arguments, /*allow_all=*/true);
  arguments.reader().require("enable", "true or false");
  const bool enable = arguments.reader().boolean_or("enable", true);
  if (auto error = arguments.finish()) return *error;
  return acknowledge("motion_en", motion_enable_request(*joint, enable));
}

Result<nlohmann::json> XarmOps::set_state(const nlohmann::json& args) {
  driver::OpArguments arguments("set_state", args, op_usage("set_state"));
  JsonReader& reader = arguments.reader();
  reader.require("state", "0, 3, 4 or 6");
  const auto state = reader.integer("state", 0, 6);
  if (state && (*state == 1 || *state == 2 || *state == 5)) {
    reader.error("state", "expected 0 (start), 3 (pause), 4 (stop) or 6 (decelerate to stop), got " +
                              std::to_string(*state) + " (a state the controller reports, not one it is set to)");
  }
  if (auto error = arguments.finish()) return *error;
  return acknowledge("set_state", set_state_request(static_cast<int>(*state)));
}

Result<nlohmann::json> XarmOps::set_mode(const nlohmann::json& args) {
  driver::OpArguments arguments("set_mode", args, op_usage("set_mode"));
  JsonReader& reader = arguments.reader();
  reader.require("mode", "0, 2, 4, 5, 6 or 7");
  const auto mode = reader.integer("mode", 0, 7);
  if (mode && (*mode == kModeServo || *mode == kModeCartesianTeach)) {
    reader.error("mode", *mode == kModeServo ? "servo mode (1) is entered by robotd while a session streams"
                                             : "Cartesian teaching (3) is not available on xArm");
  }
  if (auto error = arguments.finish()) return *error;
  if (auto refused = check_can_plan("set_mode")) return *refused;
  return acknowledge("set_mode", set_mode_request(static_cast<int>(*mode)));
}

Result<nlohmann::json> XarmOps::set_reduced_mode(const nlohmann::json& args) {
  driver::OpArguments arguments("set_reduced_mode", args, op_usage("set_reduced_mode"));
  arguments.reader().require("on", "true or false");
  const bool on = arguments.reader().boolean_or("on", false);
  if (auto error = arguments.finish()) return *error;
  return acknowledge("set_reduced_mode", set_reduced_mode_request(on));
}

Result<nlohmann::json> XarmOps::set_brake(const nlohmann::json& args) {
  driver::OpArguments arguments("set_brake", args, op_usage("set_brake"));
  const auto joint = joint_argument(arguments, /*allow_all=*/true);
  arguments.reader().require("release", "true (release the brake) or false (engage it)");
  const bool release = arguments.reader().boolean_or("release", false);
  if (auto error = arguments.finish()) return *error;
  return acknowledge("set_brake", set_brake_request(*joint, release));
}

Result<nlohmann::json> XarmOps::set_limit(const std::string& op, const nlohmann::json& args) {
  driver::OpArguments arguments(op, args, op_usage(op));
  JsonReader& reader = arguments.reader();
  const char* key = op == "set_tcp_jerk"     ? "jerk_m_s3"
                    : op == "set_tcp_maxacc" ? "acc_m_s2"
                    : op == "set_joint_jerk" ? "jerk_rad_s3"
                                             : "acc_rad_s2";
  reader.require(key, "a number");
  const auto value = reader.number(key);
  if (value) {
    const Result<void> checked = op == "set_tcp_jerk"     ? check_tcp_jerk(*value)
                                 : op == "set_tcp_maxacc" ? check_tcp_acc(*value)
                                 : op == "set_joint_jerk" ? check_joint_jerk(*value)
                                                          : check_joint_acc(*value);
    if (!checked) reader.error(key, checked.error().message);
  }
  if (auto error = arguments.finish()) return *error;
  const Request request = op == "set_tcp_jerk"     ? set_tcp_jerk_request(*value)
                          : op == "set_tcp_maxacc" ? set_tcp_maxacc_request(*value)
                          : op == "set_joint_jerk" ? set_joint_jerk_request(*value)
                                                   : set_joint_maxacc_request(*value);
  return acknowledge(op, request);
}

Result<nlohmann::json> XarmOps::set_tcp_offset(const nlohmann::json& args) {
  driver::OpArguments arguments("set_tcp_offset", args, op_usage("set_tcp_offset"));
  const auto offset = pose_argument(arguments);
  if (auto error = arguments.finish()) return *error;
  return acknowledge("set_tcp_offset", set_tcp_offset_request(*offset));
}

}  // namespace robotd::xarm
