// The argument ranges the vendor SDK (piper_sdk 0.6.1, its msg_v2/transmit classes) refuses,
// checked on robotd's frame structs before they are encoded. Texts are static: the checks run
// anywhere, the RT loop included, without allocating.
#include <cmath>
#include <cstdint>
#include <optional>

#include "piper_frames.hpp"

namespace robotd::piper {
namespace {

constexpr double kEffortUnitNm = 0.001;           // 0x159 gripper effort
constexpr double kMaxGripperEffortCounts = 5000;  // SDK: 0 … 5000 (5 N·m)
constexpr double kMaxJointSpeedCounts = 3000;     // 0x474, SDK: 0 … 3000 or 0x7FFF
constexpr double kMaxJointAccCounts = 500;        // 0x475, SDK: 0 … 500 or 0x7FFF
constexpr double kMaxEndLimitCounts = 65535;      // 0x479: a uint16 each
constexpr std::uint8_t kAllMotors = 0xFF;         // 0x471: the SDK's other spelling of "all"

/// The wire count of `value` (rounded as the codec rounds), NaN for a NaN value.
double counts(double value, double unit) { return std::round(value / unit); }
bool counts_within(double value, double unit, double highest) {
  const double n = counts(value, unit);
  return n >= 0 && n <= highest;  // false for NaN
}
bool end_limit_valid(const std::optional<double>& value) {
  return !value || counts_within(*value, kEndLimitUnit, kMaxEndLimitCounts);
}

}  // namespace

const char* refusal(const MotionControl& frame, const CodecOptions& /*options*/) {
  if (static_cast<std::uint8_t>(frame.emergency_stop) > 0x02) {
    return "0x150 emergency_stop must be 0 (none), 1 (stop) or 2 (resume)";
  }
  if (frame.track_ctrl > 0x08) return "0x150 track_ctrl must be 0 … 8";
  if (frame.drag_teach_ctrl > 0x07) return "0x150 drag_teach_ctrl must be 0 … 7";
  return nullptr;
}

const char* refusal(const ModeControl& frame, const CodecOptions& /*options*/) {
  switch (frame.ctrl_mode) {
    case ControlMode::kStandby:
    case ControlMode::kCanCommand:
    case ControlMode::kEthernet:
    case ControlMode::kWifi:
    case ControlMode::kOfflineTrajectory:
      break;
    default:
      return "0x151 ctrl_mode must be 0 (standby), 1 (CAN), 3 (Ethernet), 4 (Wi-Fi) or 7 (offline trajectory); "
             "teach, remote and linkage-teach are states the arm reports, not modes a host sets";
  }
  if (static_cast<std::uint8_t>(frame.move_mode) > static_cast<std::uint8_t>(MoveMode::kCpv)) {
    return "0x151 move_mode must be P, J, L, C, MIT or CPV";
  }
  if (frame.speed_percent > 100) return "0x151 speed_percent must be 0 … 100";
  if (frame.installation > 3) return "0x151 installation must be 0 (unchanged), 1, 2 or 3";
  return nullptr;
}

const char* refusal(const MoveCPoint& frame, const CodecOptions& /*options*/) {
  return frame.index > 3 ? "0x158 point index must be 0 … 3 (1 start, 2 middle, 3 end)" : nullptr;
}

const char* refusal(const GripperControl& frame, const CodecOptions& /*options*/) {
  if (!counts_within(frame.effort_nm, kEffortUnitNm, kMaxGripperEffortCounts)) {
    return "0x159 gripper effort must be 0 … 5 N·m";
  }
  if (static_cast<std::uint8_t>(frame.enable) > static_cast<std::uint8_t>(GripperEnable::kEnableClearError)) {
    return "0x159 gripper enable code must be 0 … 3 (disable, enable, and each with clear error)";
  }
  return nullptr;
}

const char* refusal(const MasterSlaveConfig& frame, const CodecOptions& /*options*/) {
  if (frame.linkage != 0x00 && frame.linkage != 0xFA && frame.linkage != 0xFC) {
    return "0x470 linkage must be 0x00 (none), 0xFA (leader) or 0xFC (follower)";
  }
  if (!id_offset_valid(frame.feedback_offset) || !id_offset_valid(frame.control_offset) ||
      !id_offset_valid(frame.linkage_offset)) {
    return "0x470 id offsets must be 0x00, 0x10 or 0x20";
  }
  return nullptr;
}

const char* refusal(const MotorEnable& frame, const CodecOptions& /*options*/) {
  if ((frame.motor >= 1 && frame.motor <= kAllJoints) || frame.motor == kAllMotors) return nullptr;
  return "0x471 motor must be 1 … 6, or 7 or 0xFF for all";
}

const char* refusal(const JointLimitQuery& frame, const CodecOptions& /*options*/) {
  return frame.joint >= 1 && frame.joint <= kAllJoints ? nullptr : "0x472 joint must be 1 … 6, or 7 for all";
}

const char* refusal(const JointLimitSet& frame, const CodecOptions& options) {
  if (frame.joint < 1 || frame.joint > kArmJoints) return "0x474 joint must be 1 … 6";
  if (frame.max_speed_rad_s &&
      !counts_within(*frame.max_speed_rad_s, options.max_speed_unit_rad_s, kMaxJointSpeedCounts)) {
    return "0x474 max joint speed must be 0 … 3000 counts (0 … 3 rad/s at the SDK's unit)";
  }
  return nullptr;
}

const char* refusal(const JointConfig& frame, const CodecOptions& options) {
  if (frame.joint < 1 || frame.joint > kAllJoints) return "0x475 joint must be 1 … 6, or 7 for all";
  const double acc = counts(frame.max_acc_rad_s2, options.max_acc_unit_rad_s2);
  if (!(acc >= 0 && acc <= kMaxJointAccCounts) && acc != kUnchanged) {
    return "0x475 max joint acceleration must be 0 … 500 counts (0 … 5 rad/s² at 0.01 rad/s²) or 0x7FFF (unchanged)";
  }
  return nullptr;
}

const char* refusal(const ParamEnquiry& frame, const CodecOptions& /*options*/) {
  if (frame.query > 0x04) return "0x477 query must be 0 … 4 (none, end limits, crash levels, trajectory, gripper)";
  if (frame.setting > 0x02) return "0x477 setting must be 0 … 2 (none, reset end limits, reset joint limits)";
  if (frame.feedback_48x > 0x02) return "0x477 0x48x feedback switch must be 0 (no change), 1 (on) or 2 (off)";
  if (frame.payload && *frame.payload > 0x03) return "0x477 payload must be 0 (empty), 1 (half), 2 (full) or 3";
  return nullptr;
}

const char* refusal(const EndVelAccSet& frame, const CodecOptions& /*options*/) {
  const EndVelAcc& v = frame.values;
  if (end_limit_valid(v.max_linear_velocity_m_s) && end_limit_valid(v.max_angular_velocity_rad_s) &&
      end_limit_valid(v.max_linear_acceleration_m_s2) && end_limit_valid(v.max_angular_acceleration_rad_s2)) {
    return nullptr;
  }
  return "0x479 end-effector limits must each be 0 … 65.535 (uint16 in 0.001 units)";
}

const char* refusal(const GripperParamSet& frame, const CodecOptions& /*options*/) {
  const GripperParams& p = frame.params;
  if (p.teaching_range_percent < 100 || p.teaching_range_percent > 200) {
    return "0x47D teaching range must be 100 … 200 %";
  }
  if (p.max_range_mm != 0 && p.max_range_mm != 70 && p.max_range_mm != 100) {
    return "0x47D max range must be 0, 70 or 100 mm";
  }
  if (p.teaching_friction < 1 || p.teaching_friction > 10) return "0x47D teaching friction must be 1 … 10";
  return nullptr;
}

}  // namespace robotd::piper
