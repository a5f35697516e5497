// The command registers of §4.1 by name, and the groups whose replies and side effects differ:
// motions (§2.3), queued motions, and the setters that reset the system (§3.2).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

struct RegisterName {
  Register reg;
  std::string_view name;
};

// The spec's (and the SDKs') names.
constexpr auto kRegisterNames = std::to_array<RegisterName>({
    {Register::kGetVersion, "get_version"},
    {Register::kGetRobotSn, "get_robot_sn"},
    {Register::kMotionEnable, "motion_en"},
    {Register::kSetState, "set_state"},
    {Register::kGetState, "get_state"},
    {Register::kGetCmdnum, "get_cmdnum"},
    {Register::kGetErrCode, "get_err_code"},
    {Register::kCleanErr, "clean_err"},
    {Register::kCleanWar, "clean_war"},
    {Register::kSetBrake, "set_brake"},
    {Register::kSetMode, "set_mode"},
    {Register::kMoveLine, "move_line"},
    {Register::kMoveLineB, "move_lineb"},
    {Register::kMoveJoint, "move_joint"},
    {Register::kMoveJointB, "move_jointb"},
    {Register::kMoveGohome, "move_gohome"},
    {Register::kSleepInstruction, "sleep_instruction"},
    {Register::kMoveCircle, "move_circle"},
    {Register::kMoveLineTool, "move_line_tool"},
    {Register::kServoJ, "servo_j"},
    {Register::kServoCartesian, "servo_cartesian"},
    {Register::kSetTcpJerk, "set_tcp_jerk"},
    {Register::kSetTcpMaxAcc, "set_tcp_maxacc"},
    {Register::kSetJointJerk, "set_joint_jerk"},
    {Register::kSetJointMaxAcc, "set_joint_maxacc"},
    {Register::kSetTcpOffset, "set_tcp_offset"},
    {Register::kSetLoadParam, "set_load_param"},
    {Register::kSetCollisionSensitivity, "set_collis_sens"},
    {Register::kSetTeachSensitivity, "set_teach_sens"},
    {Register::kCleanConf, "clean_conf"},
    {Register::kSaveConf, "save_conf"},
    {Register::kGetTcpPose, "get_tcp_pose"},
    {Register::kGetJointPos, "get_joint_pos"},
    {Register::kGetIk, "get_ik"},
    {Register::kGetFk, "get_fk"},
    {Register::kIsJointLimit, "is_joint_limit"},
    {Register::kIsTcpLimit, "is_tcp_limit"},
    {Register::kGetReducedMode, "get_reduced_mode"},
    {Register::kSetReducedMode, "set_reduced_mode"},
    {Register::kServoGetDbmsg, "servo_get_dbmsg"},
    {Register::kToolModbus, "tool_modbus_rtu"},
    {Register::kToolGpioError, "tool_gpio_err"},
    {Register::kToolWrite16, "tool_write_16"},
    {Register::kToolRead16, "tool_read_16"},
    {Register::kToolWrite32, "tool_write_32"},
    {Register::kToolRead32, "tool_read_32"},
    {Register::kFeedbackCheck, "feedback_check"},
    {Register::kSetFeedbackType, "set_feedback_type"},
    {Register::kMotionFeedback, "motion_feedback"},
});

constexpr auto kSystemResetters = std::to_array<Register>(
    {Register::kMotionEnable, Register::kCleanErr, Register::kSetBrake, Register::kSetMode, Register::kSetTcpOffset,
     Register::kSetCollisionSensitivity, Register::kSetTeachSensitivity});

constexpr bool in_range(std::uint8_t reg, Register first, Register last) {
  return reg >= static_cast<std::uint8_t>(first) && reg <= static_cast<std::uint8_t>(last);
}

}  // namespace

std::string register_name(std::uint8_t reg) {
  const auto found = std::find_if(kRegisterNames.begin(), kRegisterNames.end(), [reg](const RegisterName& entry) {
    return static_cast<std::uint8_t>(entry.reg) == reg;
  });
  if (found == kRegisterNames.end()) return "register " + std::to_string(reg);
  return std::string(found->name);
}

bool is_motion_register(std::uint8_t reg) { return in_range(reg, Register::kMoveLine, Register::kServoCartesian); }

bool resets_system(std::uint8_t reg) {
  return std::any_of(kSystemResetters.begin(), kSystemResetters.end(),
                     [reg](Register resetter) { return static_cast<std::uint8_t>(resetter) == reg; });
}

bool is_queued_motion(std::uint8_t reg) { return in_range(reg, Register::kMoveLine, Register::kMoveLineTool); }

}  // namespace robotd::xarm
