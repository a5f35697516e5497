// The op table, dispatch and argument reading.
#include "driver/piper_ops.hpp"

#include <algorithm>
#include <array>
#include <exception>

namespace robotd::piper {
namespace {

struct OpSpec {
  std::string_view name;
  std::string_view help;
  bool needs_free_motors = false;
};

constexpr std::array<OpSpec, 30> kOps{{
    {"end_pose",
     R"({x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad, "motion": "p"|"l", "speed_percent": 1..100}: )"
     R"(move the flange to a pose with the arm's planner, MOVE P (joint space) or MOVE L (straight line))",
     driver::kNeedsFreeMotors},
    {"move_c",
     R"({"start": pose, "middle": pose, "end": pose, "speed_percent": 1..100}: circular move )"
     R"(through three poses (MOVE C), each pose {x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad})",
     driver::kNeedsFreeMotors},
    {"mode",
     R"({"ctrl_mode": "standby"|"can"|"ethernet"|"wifi"|"offline", "move_mode": "p"|"j"|"l"|"c"|"mit"|"cpv", )"
     R"("speed_percent": 0..100, "mit": bool, "installation": "horizontal"|"side_left"|"side_right"}: ModeCtrl)",
     driver::kNeedsFreeMotors},
    {"gripper",
     R"({"stroke_m": 0..max, "effort_nm": 0..5, "enable": bool, "clear_error": bool, "set_zero": bool}: )"
     R"(GripperCtrl when no session streams the gripper joint)",
     driver::kNeedsFreeMotors},
    {"enable", R"({"joint": 1..6|"all"}: enable motors (0x471))", driver::kNeedsFreeMotors},
    {"disable", R"({"joint": 1..6|"all"}: disable motors (0x471): they lose torque at once, the arm drops)",
     driver::kNeedsFreeMotors},
    {"master_slave",
     R"({"role": "master"|"slave", "feedback_offset": 0|16|32, "control_offset": 0|16|32, )"
     R"("linkage_offset": 0|16|32}: MasterSlaveConfig (0x470))",
     driver::kNeedsFreeMotors},
    {"master_home",
     R"({"mode": "restore_linkage"|"leader_to_zero"|"both_to_zero"}: ReqMasterArmMoveToHome (0x191): )"
     R"(a leader (master) arm, or leader and follower, move to zero; restore_linkage resumes following)",
     driver::kNeedsFreeMotors},
    {"limits", R"({}: per joint angle limits (rad) and max speed (rad/s) the arm holds (0x472 → 0x473))"},
    {"acc_limits", R"({}: per joint max acceleration (rad/s²) the arm holds (0x472 → 0x47C))"},
    {"firmware", R"({}: the firmware information text and software version (0x4AF))"},
    {"end_limits", R"({}: end-effector max linear/angular velocity and acceleration (0x477 → 0x478))"},
    {"crash_protection", R"({}: collision protection level per joint, 0 off … 8 (0x477 → 0x47B))"},
    {"gripper_params", R"({}: gripper / teaching pendant parameters (0x477 → 0x47E))"},
    {"can_fps", R"({}: frames per second received from and sent to the bus, and totals)"},
    {"state", R"({}: everything the arm reports: status, modes, per joint position, speed, current, effort, )"
              R"(voltage, temperatures, driver status, enable; gripper; the arm's end pose)"},
    {"fk", R"({"joints_rad": [6 numbers]}: forward kinematics: the flange and every link's pose, as GetFK )"
           R"((measured joints if omitted))"},
    {"master_commands", R"({}: the last ModeCtrl, joint and gripper commands a master (leader) arm sent on the bus)"},
    {"fk_calculation",
     R"({"enabled": bool}: EnableFkCal / DisableFkCal: compute the flange pose (topic rt/end_pose) from the )"
     R"(measured joints each cycle, or not (answers the setting in force without "enabled"))"},
    {"trajectory_index",
     R"({}: ArmParamEnquiryAndConfig query 0x03: the arm's current trajectory index, read from the next )"
     R"(status frame (0x2A1 byte 5) after the query)"},
    {"set_joint_limits",
     R"({"joint": 1..6, "min_angle_rad", "max_angle_rad", "max_speed_rad_s"}: )"
     R"(MotorAngleLimitMaxSpdSet (0x474, saved in the joint's flash); omitted fields stay)",
     driver::kNeedsFreeMotors},
    {"set_max_speed", R"({"joint": 1..6|"all", "max_speed_rad_s": 0..3}: MotorMaxSpdSet (0x474))",
     driver::kNeedsFreeMotors},
    {"joint_config",
     R"({"joint": 1..6|"all", "set_zero": bool, "max_acc_rad_s2": 0..5, "clear_error": bool}: )"
     R"(JointConfig (0x475); set_zero makes the current position the joint's zero)",
     driver::kNeedsFreeMotors},
    {"set_max_acc", R"({"joint": 1..6|"all", "max_acc_rad_s2": 0..5}: JointMaxAccConfig (0x475))",
     driver::kNeedsFreeMotors},
    {"param_config",
     R"({"reset_end_limits": bool, "reset_joint_limits": bool, "feedback_48x": "enable"|"disable", )"
     R"("payload": "empty"|"half"|"full"}: ArmParamEnquiryAndConfig settings (0x477))",
     driver::kNeedsFreeMotors},
    {"set_end_limits",
     R"({"max_linear_velocity_m_s", "max_angular_velocity_rad_s", "max_linear_acceleration_m_s2", )"
     R"("max_angular_acceleration_rad_s2"}: EndSpdAndAccParamSet (0x479); omitted fields stay)",
     driver::kNeedsFreeMotors},
    {"set_crash_protection", R"({"levels": [6 integers 0..8]}: CrashProtectionConfig (0x47A))",
     driver::kNeedsFreeMotors},
    {"set_gripper_params",
     R"({"teaching_range_percent": 100..200, "max_range_mm": 0|70|100, )"
     R"("teaching_friction": 1..10}: GripperTeachingPendantParamConfig (0x47D))",
     driver::kNeedsFreeMotors},
    {"sdk_joint_limit",
     R"({"joint": "j1".."j6", "min_rad", "max_rad"}: SetSDKJointLimitParam: narrow a joint's position limits at )"
     R"(run time (robotd holds them from the next tick; it never widens: a wider range is refused))"},
    {"sdk_gripper_range",
     R"({"min_m", "max_m"}: SetSDKGripperRangeParam: narrow the gripper's stroke range (m) at run time, for the )"
     R"(gripper joint and the gripper op (never widens))"},
}};

// The ops a leader device runs: those that read what the driver has received, and master_slave,
// the way back to a follower. The others send the arm a motion, a setting or a query: a leader
// sends only its control frames (piper_sdk asserts/double_piper.MD) and robotd sends it nothing.
constexpr std::array<std::string_view, 6> kLeaderOps{"state",           "can_fps",        "fk",
                                                     "master_commands", "fk_calculation", "master_slave"};

std::string_view help_of(std::string_view op) {
  const auto* spec = std::find_if(kOps.begin(), kOps.end(), [&](const OpSpec& s) { return s.name == op; });
  return spec == kOps.end() ? std::string_view{} : spec->help;
}

}  // namespace

std::vector<driver::OpDescription> op_descriptions() {
  std::vector<driver::OpDescription> ops;
  ops.reserve(kOps.size());
  for (const OpSpec& op : kOps) ops.push_back({std::string(op.name), std::string(op.help), op.needs_free_motors});
  return ops;
}

OpArguments::OpArguments(std::string_view op, const nlohmann::json& args)
    : driver::OpArguments(op, args, help_of(op)) {}

std::optional<std::uint8_t> OpArguments::joint(bool allow_all) {
  if (!reader().has("joint")) {
    if (allow_all) return kAllJoints;
    reader().require("joint", "a joint number 1..6");
    return std::nullopt;
  }
  const auto given = reader().raw("joint");
  if (allow_all && given && given->is_string()) {
    if (!reader().string("joint", {"all"})) return std::nullopt;
    return kAllJoints;
  }
  const auto number = reader().integer("joint", 1, kArmJoints);
  if (!number) return std::nullopt;
  return static_cast<std::uint8_t>(*number);
}

std::optional<std::uint8_t> OpArguments::sdk_joint() {
  reader().require("joint", R"("j1" … "j6" (or 1 … 6))");
  const auto given = reader().raw("joint");
  if (!given) return std::nullopt;
  if (!given->is_string()) {
    const auto number = reader().integer("joint", 1, kArmJoints);
    if (!number) return std::nullopt;
    return static_cast<std::uint8_t>(*number);
  }
  const auto name = reader().string("joint", {"j1", "j2", "j3", "j4", "j5", "j6"});
  if (!name) return std::nullopt;
  return static_cast<std::uint8_t>(name->back() - '0');
}

std::optional<CartesianPose> OpArguments::pose(JsonReader& reader) {
  const NumberRange reach{.min = -1.0, .max = 1.0};  // m: the SDK discards poses beyond 1 m
  const NumberRange angle{.min = -3.1416, .max = 3.1416};
  for (const char* key : {"x_m", "y_m", "z_m", "roll_rad", "pitch_rad", "yaw_rad"}) {
    reader.require(key, "a number");
  }
  const auto x = reader.number("x_m", reach);
  const auto y = reader.number("y_m", reach);
  const auto z = reader.number("z_m", reach);
  const auto roll = reader.number("roll_rad", angle);
  const auto pitch = reader.number("pitch_rad", NumberRange{.min = -1.5708, .max = 1.5708});
  const auto yaw = reader.number("yaw_rad", angle);
  if (!x || !y || !z || !roll || !pitch || !yaw) return std::nullopt;
  return CartesianPose{*x, *y, *z, *roll, *pitch, *yaw};
}

Result<nlohmann::json> PiperOps::call(const std::string& op, const nlohmann::json& args) {
  const bool is_op = std::any_of(kOps.begin(), kOps.end(), [&](const OpSpec& spec) { return spec.name == op; });
  if (is_op && driver_.params_.leader() && std::find(kLeaderOps.begin(), kLeaderOps.end(), op) == kLeaderOps.end()) {
    std::string allowed;
    for (const std::string_view name : kLeaderOps) allowed += (allowed.empty() ? "" : ", ") + std::string(name);
    return make_error(ErrorCode::kRefused,
                      op + ": " + kLeaderIsReadOnly + " (a leader device runs only " + allowed + ")");
  }
  try {
    if (op == "end_pose") return end_pose(args);
    if (op == "move_c") return move_c(args);
    if (op == "mode") return mode(args);
    if (op == "gripper") return gripper(args);
    if (op == "enable") return enable(args, true);
    if (op == "disable") return enable(args, false);
    if (op == "master_slave") return master_slave(args);
    if (op == "master_home") return master_home(args);
    if (op == "limits") return limits(args);
    if (op == "acc_limits") return acc_limits(args);
    if (op == "firmware") return firmware(args);
    if (op == "end_limits") return end_limits(args);
    if (op == "crash_protection") return crash_protection(args);
    if (op == "gripper_params") return gripper_params(args);
    if (op == "can_fps") return can_fps(args);
    if (op == "state") return state(args);
    if (op == "fk") return fk(args);
    if (op == "master_commands") return master_commands(args);
    if (op == "fk_calculation") return fk_calculation(args);
    if (op == "trajectory_index") return trajectory_index(args);
    if (op == "set_joint_limits") return set_joint_limits(args);
    if (op == "set_max_speed") return set_max_speed(args);
    if (op == "joint_config") return joint_config(args);
    if (op == "set_max_acc") return set_max_acc(args);
    if (op == "param_config") return param_config(args);
    if (op == "set_end_limits") return set_end_limits(args);
    if (op == "set_crash_protection") return set_crash_protection(args);
    if (op == "set_gripper_params") return set_gripper_params(args);
    if (op == "sdk_joint_limit") return sdk_joint_limit(args);
    if (op == "sdk_gripper_range") return sdk_gripper_range(args);
  } catch (const std::exception& e) {
    return make_error(ErrorCode::kInvalidArgument, op + ": " + e.what());
  }
  std::string known;
  for (const OpSpec& spec : kOps) known += (known.empty() ? "" : ", ") + std::string(spec.name);
  return make_error(ErrorCode::kInvalidArgument, "unknown op \"" + op + "\" (the piper driver has: " + known + ")");
}

Result<nlohmann::json> PiperDriver::call(const std::string& op, const nlohmann::json& args) {
  if (!configured_) return make_error(ErrorCode::kRefused, op + ": the piper driver is not configured");
  const std::lock_guard lock(ops_mutex_);
  return PiperOps(*this).call(op, args);
}

nlohmann::json to_json(const CartesianPose& pose) {
  return {{"x_m", pose.x_m},         {"y_m", pose.y_m},          {"z_m", pose.z_m},
          {"roll_rad", pose.rx_rad}, {"pitch_rad", pose.ry_rad}, {"yaw_rad", pose.rz_rad}};
}

nlohmann::json to_json(const GripperParams& params) {
  return {{"teaching_range_percent", params.teaching_range_percent},
          {"max_range_mm", params.max_range_mm},
          {"teaching_friction", params.teaching_friction}};
}

nlohmann::json to_json(const EndVelAcc& values) {
  const auto value = [](const std::optional<double>& field) { return field ? nlohmann::json(*field) : nullptr; };
  return {{"max_linear_velocity_m_s", value(values.max_linear_velocity_m_s)},
          {"max_angular_velocity_rad_s", value(values.max_angular_velocity_rad_s)},
          {"max_linear_acceleration_m_s2", value(values.max_linear_acceleration_m_s2)},
          {"max_angular_acceleration_rad_s2", value(values.max_angular_acceleration_rad_s2)}};
}

}  // namespace robotd::piper
