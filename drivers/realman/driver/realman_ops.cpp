// The op table, dispatch, argument reading and sending.
#include "driver/realman_ops.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>

namespace robotd::realman {
namespace {

struct OpSpec {
  std::string_view name;
  std::string_view help;
  bool needs_free_motors = false;
};

constexpr std::array<OpSpec, 33> kOps{{
    {"movej",
     R"({"joints_rad": [dof], "v": 1..100 %, "r": 0..100 %, "trajectory_connect": bool, "block", )"
     R"("timeout_s"}: planned joint move (movej))",
     driver::kNeedsFreeMotors},
    {"movel",
     R"({"x_m", "y_m", "z_m", "rx_rad", "ry_rad", "rz_rad", "v", "r", "trajectory_connect", "block", )"
     R"("timeout_s"}: straight line to a pose in the work frame (movel))",
     driver::kNeedsFreeMotors},
    {"movej_p",
     R"({"x_m", "y_m", "z_m", "rx_rad", "ry_rad", "rz_rad", "v", "r", "trajectory_connect", "block", )"
     R"("timeout_s"}: joint-space move to a pose (movej_p))",
     driver::kNeedsFreeMotors},
    {"set_arm_stop", R"({}: quick stop of the trajectory)", driver::kNeedsFreeMotors},
    {"set_arm_slow_stop", R"({}: decelerate and stop on the path)", driver::kNeedsFreeMotors},
    {"set_arm_pause", R"({}: pause on the path (resume with set_arm_continue))", driver::kNeedsFreeMotors},
    {"set_arm_continue", R"({}: resume a paused trajectory)", driver::kNeedsFreeMotors},
    {"set_delete_current_trajectory", R"({}: drop the current trajectory (after a pause))", driver::kNeedsFreeMotors},
    {"set_arm_delete_trajectory", R"({}: drop every queued trajectory (after a pause))", driver::kNeedsFreeMotors},
    {"set_joint_en_state", R"({"joint": 1..dof, "enable": bool}: enable or disable one joint)",
     driver::kNeedsFreeMotors},
    {"set_joint_clear_err", R"({"joint": 1..dof}: clear one joint's error)", driver::kNeedsFreeMotors},
    {"clear_system_err", R"({}: clear the controller's system error)", driver::kNeedsFreeMotors},
    {"set_arm_power", R"({"on": bool}: switch the arm's power)", driver::kNeedsFreeMotors},
    {"set_gripper_route", R"({"min": 0..1000, "max": 0..1000}: the gripper's opening limits (kept by the gripper))"},
    {"set_gripper_release", R"({"speed": 1..1000, "block", "timeout_s"}: open the gripper)"},
    {"set_gripper_pick", R"({"speed": 1..1000, "force": 50..1000, "block", "timeout_s"}: close until the force )"
                         R"(threshold)"},
    {"set_gripper_pick_on", R"({"speed": 1..1000, "force": 50..1000, "block", "timeout_s"}: close and keep )"
                            R"(re-gripping when the force drops)"},
    {"set_gripper_position", R"({"position": 1..1000, "block", "timeout_s"}: move the gripper to an opening)"},
    {"get_gripper_state", R"({}: enabled, online, error bits and text, mode, force (g), temperature (°C), opening)"},
    {"set_hand_posture", R"({"posture": 1..40, "block", "timeout_s"}: a posture stored in the hand)"},
    {"set_hand_seq", R"({"sequence": 1..40, "block", "timeout_s"}: an action sequence stored in the hand)"},
    {"set_hand_angle", R"({"angles": [6] 0..1000 or -1 (keep), "block", "timeout_s"}: finger angles: little, )"
                       R"(ring, middle, index, thumb bend, thumb rotation)"},
    {"set_hand_speed", R"({"speed": 1..1000}: the fingers' speed)"},
    {"set_hand_force", R"({"force": 1..1000}: the fingers' force threshold)"},
    {"get_current_arm_state", R"({}: joints (rad), pose (m, rad) and the controller's errors)"},
    {"get_joint_err_flag", R"({}: each joint's error bits and text, and whether its brake is released)"},
    {"get_joint_en_state", R"({}: whether each joint is enabled)"},
    {"get_arm_all_state", R"({}: each joint's temperature (°C), current (A), voltage (V), enable and errors)"},
    {"get_controller_state", R"({}: the controller's voltage (V), current (A), temperature (°C) and error)"},
    {"get_arm_software_info", R"({}: the controller's reply as is (model, firmware versions))"},
    {"get_realtime_push", R"({}: the controller's UDP push settings as is)"},
    {"get_arm_power_state", R"({}: whether the arm is powered)"},
    {"state", R"({}: what robotd last received: joints, pose, errors, arm status, link counters)"},
}};

std::string_view help_of(std::string_view op) {
  const auto* spec = std::find_if(kOps.begin(), kOps.end(), [&](const OpSpec& s) { return s.name == op; });
  return spec == kOps.end() ? std::string_view{} : spec->help;
}

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

}  // namespace

std::vector<driver::OpDescription> op_descriptions() {
  std::vector<driver::OpDescription> ops;
  ops.reserve(kOps.size());
  for (const OpSpec& op : kOps) ops.push_back({std::string(op.name), std::string(op.help), op.needs_free_motors});
  return ops;
}

OpArguments::OpArguments(std::string_view op, const nlohmann::json& args)
    : driver::OpArguments(op, args, help_of(op)) {}

bool OpArguments::block() { return reader().boolean_or("block", true); }

double OpArguments::timeout_s() { return reader().number_or("timeout_s", 60, NumberRange{.min = 0.1, .max = 3600}); }

Result<nlohmann::json> RealmanOps::call(const std::string& op, const nlohmann::json& args) {
  try {
    if (op == "movej") return movej(args);
    if (op == "movel" || op == "movej_p") return cartesian_move(op, args);
    if (op == "set_joint_en_state") return set_joint_en_state(args);
    if (op == "set_joint_clear_err") return set_joint_clear_err(args);
    if (op == "set_arm_power") return set_arm_power(args);
    if (op == "get_gripper_state") return get_gripper_state(args);
    if (starts_with(op, "set_gripper_")) return gripper(op, args);
    if (starts_with(op, "set_hand_")) return hand(op, args);
    if (op == "get_current_arm_state") return get_current_arm_state(args);
    if (op == "get_joint_err_flag") return get_joint_err_flag(args);
    if (op == "get_joint_en_state") return get_joint_en_state(args);
    if (op == "get_arm_all_state") return get_arm_all_state(args);
    if (op == "get_controller_state") return get_controller_state(args);
    if (op == "get_arm_software_info" || op == "get_realtime_push" || op == "get_arm_power_state") {
      return verbatim(op, args);
    }
    if (op == "state") return state(args);
    if (!help_of(op).empty()) return plain(op, args);  // the stops and clear_system_err
  } catch (const std::exception& e) {
    return make_error(ErrorCode::kInvalidArgument, op + ": " + e.what());
  }
  std::string known;
  for (const OpSpec& spec : kOps) known += (known.empty() ? "" : ", ") + std::string(spec.name);
  return make_error(ErrorCode::kInvalidArgument, "unknown op \"" + op + "\" (the realman driver has: " + known + ")");
}

Result<nlohmann::json> RealmanOps::send(const nlohmann::json& message, std::optional<Device> block_device,
                                        double timeout_s) {
  RequestOptions options = driver_.default_options();
  options.completion = block_device;
  options.completion_timeout = std::chrono::milliseconds(std::llround(timeout_s * 1000));
  auto reply = request(message, options);
  if (!reply) return reply.error();
  nlohmann::json result = {{"accepted", true}};
  if (reply.value().completion) result["completed"] = reply.value().completion->reached;
  return result;
}

Result<ControllerLink::Reply> RealmanOps::request(const nlohmann::json& message) {
  return request(message, driver_.default_options());
}

Result<ControllerLink::Reply> RealmanOps::request(const nlohmann::json& message, const RequestOptions& options) {
  if (!driver_.connected_.load(std::memory_order_acquire)) {
    return make_error(ErrorCode::kRefused, message.value("command", "") +
                                               ": not connected to the RealMan controller at " +
                                               driver_.params_.controller.to_string());
  }
  return driver_.request(message, options);
}

}  // namespace robotd::realman
