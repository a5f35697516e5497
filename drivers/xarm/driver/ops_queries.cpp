// Queries, answered in robotd's units with the controller's codes translated to text.
#include <cmath>

#include "driver/xarm_ops.hpp"

namespace robotd::xarm {
namespace {

/// Reads the op's (empty) arguments; the error when there were any.
std::optional<Error> no_arguments(std::string_view op, const nlohmann::json& args) {
  driver::OpArguments arguments(op, args, op_usage(op));
  return arguments.finish();
}

std::string servo_state_text(int state) {
  switch (state) {
    case 0:
      return "normal";
    case 1:
      return "error detected";
    case 3:
      return "communication failure";
    default:
      return "unknown servo state " + std::to_string(state);
  }
}

}  // namespace

template <class Parse, class Fill>
Result<nlohmann::json> XarmOps::answer(std::string_view op, const Request& request, Parse parse, Fill fill) {
  auto reply = exchange(op, request);
  if (!reply) return reply.error();
  auto value = parse(ByteView(reply.value().data));
  if (!value) return value.error();
  nlohmann::json result = execution_of(reply.value());
  fill(result, value.value());
  return result;
}

Result<nlohmann::json> XarmOps::get_state(const nlohmann::json& args) {
  if (auto error = no_arguments("get_state", args)) return *error;
  return answer("get_state", plain_request(Register::kGetState), parse_state, [](nlohmann::json& out, int state) {
    out["state"] = state;
    out["state_text"] = motion_state_text(state);
  });
}

Result<nlohmann::json> XarmOps::get_cmdnum(const nlohmann::json& args) {
  if (auto error = no_arguments("get_cmdnum", args)) return *error;
  return answer("get_cmdnum", plain_request(Register::kGetCmdnum), parse_cmdnum,
                [](nlohmann::json& out, std::uint16_t count) { out["cmdnum"] = count; });
}

Result<nlohmann::json> XarmOps::get_err_code(const nlohmann::json& args) {
  if (auto error = no_arguments("get_err_code", args)) return *error;
  return answer("get_err_code", plain_request(Register::kGetErrCode), parse_err_code,
                [](nlohmann::json& out, const ErrorWarning& codes) {
                  out["error"] = codes.error;
                  out["error_text"] = controller_error_text(codes.error);
                  out["warning"] = codes.warning;
                  out["warning_text"] = controller_warning_text(codes.warning);
                });
}

Result<nlohmann::json> XarmOps::get_tcp_pose(const nlohmann::json& args) {
  if (auto error = no_arguments("get_tcp_pose", args)) return *error;
  return answer("get_tcp_pose", plain_request(Register::kGetTcpPose), parse_pose,
                [](nlohmann::json& out, const Pose& pose) { out.update(pose_json(pose)); });
}

Result<nlohmann::json> XarmOps::get_joint_pose(const nlohmann::json& args) {
  if (auto error = no_arguments("get_joint_pose", args)) return *error;
  return answer("get_joint_pose", plain_request(Register::kGetJointPos), parse_joints,
                [this](nlohmann::json& out, const JointValues& joints) { out["joints_rad"] = joints_json(joints); });
}

Result<nlohmann::json> XarmOps::get_fk(const nlohmann::json& args) {
  driver::OpArguments arguments("get_fk", args, op_usage("get_fk"));
  const auto joints = joints_argument(arguments);
  if (auto error = arguments.finish()) return *error;
  return answer("get_fk", get_fk_request(*joints), parse_pose,
                [](nlohmann::json& out, const Pose& pose) { out.update(pose_json(pose)); });
}

Result<nlohmann::json> XarmOps::is_joint_limit(const nlohmann::json& args) {
  driver::OpArguments arguments("is_joint_limit", args, op_usage("is_joint_limit"));
  const auto joints = joints_argument(arguments);
  if (auto error = arguments.finish()) return *error;
  return answer("is_joint_limit", is_joint_limit_request(*joints), parse_limit_flag,
                [](nlohmann::json& out, bool outside) { out["outside_limits"] = outside; });
}

Result<nlohmann::json> XarmOps::get_reduced_mode(const nlohmann::json& args) {
  if (auto error = no_arguments("get_reduced_mode", args)) return *error;
  return answer("get_reduced_mode", plain_request(Register::kGetReducedMode), parse_reduced_mode,
                [](nlohmann::json& out, bool on) { out["reduced_mode"] = on; });
}

Result<nlohmann::json> XarmOps::servo_get_dbmsg(const nlohmann::json& args) {
  if (auto error = no_arguments("servo_get_dbmsg", args)) return *error;
  const std::size_t dof = driver_.params_.model.dof;
  return answer("servo_get_dbmsg", plain_request(Register::kServoGetDbmsg), parse_servo_dbmsg,
                [dof](nlohmann::json& out, const std::array<ServoStatus, 8>& servos) {
                  nlohmann::json list = nlohmann::json::array();
                  for (std::size_t i = 0; i < servos.size(); ++i) {
                    const bool gripper = i == servos.size() - 1;
                    if (!gripper && i >= dof) continue;
                    list.push_back({{"servo", gripper ? std::string("gripper") : "joint" + std::to_string(i + 1)},
                                    {"state", servos[i].state},
                                    {"state_text", servo_state_text(servos[i].state)},
                                    {"error", servos[i].error},
                                    {"error_text", servo_error_text(servos[i].error)}});
                  }
                  out["servos"] = std::move(list);
                });
}

Result<nlohmann::json> XarmOps::get_version(const nlohmann::json& args) {
  if (auto error = no_arguments("get_version", args)) return *error;
  return answer("get_version", plain_request(Register::kGetVersion), parse_version,
                [](nlohmann::json& out, const Version& version) {
                  const auto model = model_for_type(version.axes, version.type);
                  out["axes"] = version.axes;
                  out["type"] = version.type;
                  out["model"] = model ? std::string(model->name) : "unknown";
                  out["robot_sn"] = version.robot_sn;
                  out["control_box_sn"] = version.control_box_sn;
                  out["firmware"] = version.firmware;
                });
}

Result<nlohmann::json> XarmOps::state(const nlohmann::json& args) {
  if (auto error = no_arguments("state", args)) return *error;
  const ArmFeedback feedback = driver_.link_.feedback();
  const LinkCounters counters = driver_.link_.counters();
  return nlohmann::json{
      {"connected", driver_.connected_.load()},
      {"joints_rad", joints_json(feedback.position_rad)},
      {"velocity_rad_s", joints_json(feedback.velocity_rad_s)},
      {"effort", joints_json(feedback.effort)},
      {"state", feedback.state},
      {"state_text", motion_state_text(feedback.state)},
      {"mode", feedback.mode},
      {"mode_text", mode_text(feedback.mode)},
      {"cmdnum", feedback.cmd_num},
      {"error", feedback.error_code},
      {"error_text", controller_error_text(feedback.error_code)},
      {"warning", feedback.warning_code},
      {"warning_text", controller_warning_text(feedback.warning_code)},
      {"servo_phase", std::string(servo_phase_name(feedback.phase))},
      {"fault", feedback.fault.text.data()},
      {"reports", counters.reports},
      {"servo_frames", counters.servo_frames},
      {"clipped_frames", counters.clipped_frames},
      {"skipped_frames", counters.skipped_frames},
      {"servo_entries", counters.servo_entries},
      {"requests", counters.requests},
      {"timeouts", counters.timeouts},
      {"unmatched", counters.unmatched},
  };
}

}  // namespace robotd::xarm
