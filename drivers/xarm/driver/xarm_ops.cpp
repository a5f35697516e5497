// The op table, dispatch, argument reading and judging the control box's replies.
#include "driver/xarm_ops.hpp"

#include <algorithm>
#include <array>
#include <exception>

namespace robotd::xarm {
namespace {

struct OpSpec {
  std::string_view name;
  std::string_view usage;
  bool needs_free_motors = false;
};

constexpr std::array<OpSpec, 40> kOps{{
    {"motion_en", R"({"joint": 1..dof or "all", "enable": bool}: enable or disable joint motors (resets the system))",
     driver::kNeedsFreeMotors},
    {"set_state", R"({"state": 0 start | 3 pause | 4 stop | 6 decelerate to stop}: the motion state)",
     driver::kNeedsFreeMotors},
    {"set_mode",
     R"({"mode": 0 position | 2 joint teaching | 4..7}: the control mode (servo, 1, is robotd's while )"
     R"(a session streams; resets the system))",
     driver::kNeedsFreeMotors},
    {"get_state", R"({}: the motion state (1 moving, 2 sleeping, 3 paused, 4 stopped, 5 reset) and its text)"},
    {"get_cmdnum", R"({}: the number of queued motion commands)"},
    {"get_err_code", R"({}: the controller's error and warning codes and their texts)"},
    {"clean_err", R"({}: clear the error (resets the system: set_state 0 to move again))", driver::kNeedsFreeMotors},
    {"clean_war", R"({}: clear the warning)"},
    {"set_brake",
     R"({"joint": 1..dof or "all", "release": bool}: release or engage joint brakes. CAUTION: a )"
     R"(released joint without motor power falls)",
     driver::kNeedsFreeMotors},
    {"move_line",
     R"({"x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad", "speed_m_s" (0.1), "acc_m_s2" (2), )"
     R"("mvtime_s" (0), "wait" (false), "timeout_s" (60)}: straight line of the TCP to a base-frame pose)",
     driver::kNeedsFreeMotors},
    {"move_lineb",
     R"({pose as move_line, "speed_m_s", "acc_m_s2", "mvtime_s", "radius_m" (0), "wait", )"
     R"("timeout_s"}: straight line blended into the next move)",
     driver::kNeedsFreeMotors},
    {"move_joint",
     R"({"joints_rad": [dof], "speed_rad_s" (0.35), "acc_rad_s2" (8), "mvtime_s" (0), "wait" )"
     R"((false), "timeout_s" (60)}: joint-space move)",
     driver::kNeedsFreeMotors},
    {"move_gohome",
     R"({"speed_rad_s" (0.35), "acc_rad_s2" (8), "mvtime_s" (0), "wait" (false), "timeout_s" )"
     R"((60)}: joint-space move to all zeros)",
     driver::kNeedsFreeMotors},
    {"sleep_instruction", R"({"seconds": 0..3600}: a queued pause between moves)", driver::kNeedsFreeMotors},
    {"set_tcp_jerk", R"({"jerk_m_s3": (0, 100]}: TCP jerk)", driver::kNeedsFreeMotors},
    {"set_tcp_maxacc", R"({"acc_m_s2": (0, 50]}: TCP maximum acceleration)", driver::kNeedsFreeMotors},
    {"set_joint_jerk", R"({"jerk_rad_s3": (0, 500]}: joint jerk)", driver::kNeedsFreeMotors},
    {"set_joint_maxacc", R"({"acc_rad_s2": (0, 20]}: joint maximum acceleration)", driver::kNeedsFreeMotors},
    {"set_tcp_offset",
     R"({"x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad"}: the TCP relative to the )"
     R"(flange (resets the system))",
     driver::kNeedsFreeMotors},
    {"clean_conf", R"({}: restore the controller's default settings)", driver::kNeedsFreeMotors},
    {"save_conf", R"({}: keep the current settings (TCP offset, limits) across controller restarts)"},
    {"get_tcp_pose", R"({}: the TCP pose: x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad)"},
    {"get_joint_pose", R"({}: the joint angles: joints_rad)"},
    {"get_fk", R"({"joints_rad": [dof]}: the TCP pose those joints give)"},
    {"is_joint_limit", R"({"joints_rad": [dof]}: whether those joints are outside the limits)"},
    {"servo_get_dbmsg", R"({}: each joint's (and the gripper's) servo state and error code, with texts)"},
    {"get_version", R"({}: axes, device type, model, serial numbers and firmware)"},
    {"get_reduced_mode", R"({}: whether the controller's reduced mode is on (firmware ≥ 1.2.0))"},
    {"set_reduced_mode",
     R"({"on": bool}: switch the controller's reduced mode (its reduced TCP and joint speeds, boundary and )"
     R"(joint ranges, set in UFACTORY Studio) on or off)",
     driver::kNeedsFreeMotors},
    {"feedback_check", R"({}: a no-op round trip to the control box)"},
    {"state", R"({}: what robotd last received: joints, state, mode, codes, servo phase, link counters)"},
    {"gripper_enable", R"({"enable": bool}: switch the xArm gripper's motor on or off (tool RS-485, 2 Mbit/s))"},
    {"gripper_set_speed", R"({"speed_rpm": 1..5000}: the gripper's speed for its next moves)"},
    {"gripper_set_position",
     R"({"position": -10..850 pulses (0 closed, 850 open), "speed_rpm" (unchanged), "wait" (false), )"
     R"("timeout_s" (10)}: move the gripper; with wait, until it is there or stops on an object)"},
    {"gripper_open", R"({"speed_rpm", "wait", "timeout_s"}: gripper_set_position to 850 (open))"},
    {"gripper_close", R"({"speed_rpm", "wait", "timeout_s"}: gripper_set_position to 0 (closed))"},
    {"gripper_get_position", R"({}: the gripper's position in pulses)"},
    {"gripper_get_error", R"({}: the gripper's error code and text (0: none))"},
    {"gripper_get_status",
     R"({}: the gripper's status: 0 stopped, 1 moving, 2 gripping an object (gripper firmware ≥ 3.4.3))"},
    {"gripper_clean_error", R"({}: clear the gripper's error (enable it again afterwards))"},
}};

}  // namespace

std::string_view op_usage(std::string_view op) {
  const auto* spec = std::find_if(kOps.begin(), kOps.end(), [&](const OpSpec& s) { return s.name == op; });
  return spec == kOps.end() ? std::string_view{} : spec->usage;
}

std::vector<driver::OpDescription> op_descriptions() {
  std::vector<driver::OpDescription> ops;
  ops.reserve(kOps.size());
  for (const OpSpec& op : kOps) ops.push_back({std::string(op.name), std::string(op.usage), op.needs_free_motors});
  return ops;
}

Result<nlohmann::json> XarmOps::call(const std::string& op, const nlohmann::json& args) {
  try {
    if (op == "move_line" || op == "move_lineb") return move_line(op, args);
    if (op == "move_joint") return move_joint(args);
    if (op == "move_gohome") return move_gohome(args);
    if (op == "sleep_instruction") return sleep_instruction(args);
    if (op == "motion_en") return motion_en(args);
    if (op == "set_state") return set_state(args);
    if (op == "set_mode") return set_mode(args);
    if (op == "set_brake") return set_brake(args);
    if (op == "set_tcp_jerk" || op == "set_tcp_maxacc" || op == "set_joint_jerk" || op == "set_joint_maxacc") {
      return set_limit(op, args);
    }
    if (op == "set_tcp_offset") return set_tcp_offset(args);
    if (op == "clean_err") return plain(op, Register::kCleanErr, args);
    if (op == "clean_war") return plain(op, Register::kCleanWar, args);
    if (op == "clean_conf") return plain(op, Register::kCleanConf, args);
    if (op == "save_conf") return plain(op, Register::kSaveConf, args);
    if (op == "feedback_check") return plain(op, Register::kFeedbackCheck, args);
    if (op == "get_state") return get_state(args);
    if (op == "get_cmdnum") return get_cmdnum(args);
    if (op == "get_err_code") return get_err_code(args);
    if (op == "get_tcp_pose") return get_tcp_pose(args);
    if (op == "get_joint_pose") return get_joint_pose(args);
    if (op == "get_fk") return get_fk(args);
    if (op == "is_joint_limit") return is_joint_limit(args);
    if (op == "servo_get_dbmsg") return servo_get_dbmsg(args);
    if (op == "get_version") return get_version(args);
    if (op == "get_reduced_mode") return get_reduced_mode(args);
    if (op == "set_reduced_mode") return set_reduced_mode(args);
    if (op == "state") return state(args);
    if (op == "gripper_enable") return gripper_enable(args);
    if (op == "gripper_set_speed") return gripper_set_speed(args);
    if (op == "gripper_set_position" || op == "gripper_open" || op == "gripper_close") return gripper_move(op, args);
    if (op == "gripper_get_position") return gripper_get_position(args);
    if (op == "gripper_get_error") return gripper_get_error(args);
    if (op == "gripper_get_status") return gripper_get_status(args);
    if (op == "gripper_clean_error") return gripper_clean_error(args);
  } catch (const std::exception& e) {
    return make_error(ErrorCode::kInvalidArgument, op + ": " + e.what());
  }
  std::string known;
  for (const OpSpec& spec : kOps) known += (known.empty() ? "" : ", ") + std::string(spec.name);
  return make_error(ErrorCode::kInvalidArgument, "unknown op \"" + op + "\" (the xarm driver has: " + known + ")");
}

std::optional<Error> XarmOps::check_connected(std::string_view op) const {
  if (driver_.connected_.load(std::memory_order_acquire)) return std::nullopt;
  return make_error(ErrorCode::kRefused, std::string(op) + ": not connected to the xArm control box at " +
                                             driver_.params_.controller.to_string());
}

Result<Reply> XarmOps::exchange(std::string_view op, const Request& request) {
  if (auto refused = check_connected(op)) return *refused;
  auto reply = driver_.request(request);
  if (!reply) return make_error(reply.error().code, std::string(op) + ": " + reply.error().message);
  const int code = execution_state(reply.value());
  if (execution_succeeded(request.reg, code)) return reply;
  std::string why = std::string(op) + ": " + execution_state_text(code);
  if (code == kExecErrorActive || code == kExecWarningActive || code == kExecInvalidResult) {
    if (auto codes = driver_.request(plain_request(Register::kGetErrCode))) {
      if (auto parsed = parse_err_code(codes.value().data)) {
        if (parsed.value().error != 0) why += ": " + controller_error_text(parsed.value().error);
        if (parsed.value().warning != 0) why += ": " + controller_warning_text(parsed.value().warning);
      }
    }
  }
  return make_error(ErrorCode::kRefused, why);
}

Result<nlohmann::json> XarmOps::acknowledge(std::string_view op, const Request& request) {
  auto reply = exchange(op, request);
  if (!reply) return reply.error();
  return execution_of(reply.value());
}

nlohmann::json XarmOps::execution_of(const Reply& reply) {
  const int code = execution_state(reply);
  return {{"execution_state", code}, {"execution_text", execution_state_text(code)}};
}

std::optional<int> XarmOps::joint_argument(driver::OpArguments& arguments, bool allow_all) const {
  JsonReader& reader = arguments.reader();
  const auto dof = static_cast<std::int64_t>(driver_.params_.model.dof);
  reader.require("joint", allow_all ? "a joint number 1.." + std::to_string(dof) + " or \"all\""
                                    : "a joint number 1.." + std::to_string(dof));
  const auto given = reader.raw("joint");
  if (allow_all && given && given->is_string()) {
    if (!reader.string("joint", {"all"})) return std::nullopt;
    return 8;
  }
  const auto number = reader.integer("joint", 1, dof);
  if (!number) return std::nullopt;
  return static_cast<int>(*number);
}

std::optional<JointValues> XarmOps::joints_argument(driver::OpArguments& arguments) const {
  JsonReader& reader = arguments.reader();
  const std::size_t dof = driver_.params_.model.dof;
  reader.require("joints_rad", "an array of " + std::to_string(dof) + " joint angles (rad)");
  const auto joints = reader.number_array("joints_rad", NumberRange{.min = -12.6, .max = 12.6});
  if (!joints) return std::nullopt;
  if (joints->size() != dof) {
    reader.error("joints_rad", "expected " + std::to_string(dof) + " angles, got " + std::to_string(joints->size()));
    return std::nullopt;
  }
  JointValues out{};
  std::copy(joints->begin(), joints->end(), out.begin());
  return out;
}

std::optional<Pose> XarmOps::pose_argument(driver::OpArguments& arguments) {
  JsonReader& reader = arguments.reader();
  const NumberRange reach{.min = -2.0, .max = 2.0};
  const NumberRange angle{.min = -3.1416, .max = 3.1416};
  for (const char* key : {"x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad"}) reader.require(key, "a number");
  const auto x = reader.number("x_m", reach);
  const auto y = reader.number("y_m", reach);
  const auto z = reader.number("z_m", reach);
  const auto roll = reader.number("roll_rad", angle);
  const auto pitch = reader.number("pitch_rad", angle);
  const auto yaw = reader.number("yaw_rad", angle);
  if (!x || !y || !z || !roll || !pitch || !yaw) return std::nullopt;
  return Pose{.position_m = {*x, *y, *z}, .rpy_rad = {*roll, *pitch, *yaw}};
}

nlohmann::json XarmOps::pose_json(const Pose& pose) {
  return {{"x_m", pose.position_m[0]},   {"y_m", pose.position_m[1]},    {"z_m", pose.position_m[2]},
          {"roll_rad", pose.rpy_rad[0]}, {"pitch_rad", pose.rpy_rad[1]}, {"yaw_rad", pose.rpy_rad[2]}};
}

nlohmann::json XarmOps::joints_json(const JointValues& joints) const {
  return std::vector<double>(joints.begin(), joints.begin() + static_cast<std::ptrdiff_t>(driver_.params_.model.dof));
}

}  // namespace robotd::xarm
