// What the arm last reported, assembled from its feedback frames on the RT thread, and the
// fault it amounts to. Trivially copyable: the RT thread publishes it for diagnostics and ops.
#pragma once

#include <array>
#include <cstdint>

#include "codec/piper_frames.hpp"
#include "robotd/driver/types.hpp"

namespace robotd::piper {

struct JointReport {
  double position_rad = 0;  // 0x2A5–0x2A7
  double speed_rad_s = 0;   // 0x251–0x256
  double current_a = 0;     //
  double motor_position_rad = 0;
  double voltage_v = 0;  // 0x261–0x266
  int driver_temperature_c = 0;
  int motor_temperature_c = 0;
  std::uint8_t driver_status = 0;
  double bus_current_a = 0;
  bool low_speed_seen = false;

  bool enabled() const { return (driver_status & 0x40U) != 0; }
};

struct ArmState {
  ArmStatus status;
  bool status_seen = false;
  std::array<JointReport, kArmJoints> joints{};
  std::uint8_t joint_pairs_seen = 0;  // bit per 0x2A5–0x2A7 frame since the last complete set
  bool joints_seen = false;           // all three joint frames have arrived at least once
  CartesianPose end_pose;             // 0x2A2–0x2A4, the arm's own kinematics
  GripperFeedback gripper;
  bool gripper_seen = false;
  // Commands a master (leader) arm sends on a shared bus (spec §5.15); a leader device's joints.
  ModeControl master_mode;
  std::array<double, kArmJoints> master_joints_rad{};
  GripperControl master_gripper;
  bool master_seen = false;
  bool master_gripper_seen = false;
  std::uint8_t master_pairs_seen = 0;   // bit per 0x155–0x157 frame since the last complete set
  bool master_joints_seen = false;      // all three joint command frames have arrived at least once
  std::uint64_t master_joint_sets = 0;  // complete sets of 0x155–0x157 so far
  std::int64_t last_master_joints_ns = 0;
  std::int64_t last_status_ns = 0;
  std::int64_t last_joints_ns = 0;
  std::uint64_t frames = 0;              // decoded frames from the arm
  std::uint64_t unknown_frames = 0;      // ids the codec does not know or frames it rejects
  std::uint64_t implausible_frames = 0;  // feedback with impossible values, dropped as the SDK does

  bool all_enabled() const;
};

/// Applies one decoded arm frame; drops (and counts) one with impossible values (plausible()).
/// Returns true when it completed a set of joint positions.
bool apply_frame(ArmState& state, const Frame& frame, std::int64_t now_ns) noexcept;

/// A fault the arm reports (status code, joint communication errors, driver fault bits,
/// gripper faults), or code 0. `own_estop`: robotd asked for the emergency stop, so the arm's
/// e-stop status is expected, not a fault. No allocation.
driver::FaultInfo arm_fault(const ArmState& state, bool own_estop, bool with_gripper) noexcept;

/// FaultInfo codes (docs/drivers/piper.md): 1–15 the 0x2A1 arm status; 100 + j joint j's
/// communication error; 200 + j joint j's driver status; 300 the gripper.
inline constexpr std::int32_t kJointCommFaultBase = 100;
inline constexpr std::int32_t kDriverFaultBase = 200;
inline constexpr std::int32_t kGripperFault = 300;

}  // namespace robotd::piper
