#include "feedback.hpp"

#include <cmath>

namespace robotd::piper::sim {
namespace {

// Motor current ↔ torque as the SDK converts it (effort = current × k, spec §5.5).
constexpr std::array<double, kArmJoints> kNmPerAmp = {1.18125, 1.18125, 1.18125, 0.95844, 0.95844, 0.95844};
constexpr double kBusVoltageV = 24.0;
constexpr int kDriverTemperatureC = 32;
constexpr int kMotorTemperatureC = 30;
constexpr std::uint8_t kEnabledBit = 0x40;  // 0x261–0x266 byte 5 and 0x2A8 byte 6
constexpr std::uint8_t kHomedBit = 0x80;    // 0x2A8 byte 6

}  // namespace

void append_high_rate_feedback(const ArmModel& arm, const CodecOptions& options, std::vector<CanMessage>& out) {
  out.push_back(encode(arm.status_frame(), options));
  for (const CanMessage& frame : encode_end_pose_feedback(arm.end_pose())) out.push_back(frame);
  for (const CanMessage& frame : encode_joint_feedback(arm.positions())) out.push_back(frame);

  const SimGripper& gripper = arm.gripper();
  GripperFeedback gripper_frame;
  gripper_frame.stroke_m = gripper.stroke_m;
  gripper_frame.effort_nm = gripper.effort_nm;
  gripper_frame.status_bits = static_cast<std::uint8_t>(gripper.injected_bits | (gripper.enabled ? kEnabledBit : 0) |
                                                        (gripper.homed ? kHomedBit : 0));
  out.push_back(encode(gripper_frame, options));

  for (std::size_t i = 0; i < arm.joints().size(); ++i) {
    const SimJoint& joint = arm.joints()[i];
    HighSpeedInfo info;
    info.joint = static_cast<int>(i) + 1;
    info.speed_rad_s = joint.velocity_rad_s;
    info.current_a = joint.torque_nm / kNmPerAmp[i];
    info.position_rad = joint.position_rad;
    out.push_back(encode(info, options));
  }
}

void append_leader_commands(const ArmModel& arm, const CodecOptions& options, std::vector<CanMessage>& out) {
  out.push_back(
      encode(ModeControl{.ctrl_mode = ControlMode::kCanCommand, .move_mode = MoveMode::kJ, .mit = true}, options));
  for (const CanMessage& frame : encode_joint_targets(arm.positions())) out.push_back(frame);
  const SimGripper& gripper = arm.gripper();
  out.push_back(encode(
      GripperControl{
          .stroke_m = gripper.stroke_m, .effort_nm = gripper.commanded_effort_nm, .enable = GripperEnable::kEnable},
      options));
}

void append_low_rate_feedback(const ArmModel& arm, const CodecOptions& options, std::vector<CanMessage>& out) {
  for (std::size_t i = 0; i < arm.joints().size(); ++i) {
    const SimJoint& joint = arm.joints()[i];
    LowSpeedInfo info;
    info.joint = static_cast<int>(i) + 1;
    info.voltage_v = kBusVoltageV;
    info.driver_temperature_c = kDriverTemperatureC;
    info.motor_temperature_c = kMotorTemperatureC;
    info.status_bits = static_cast<std::uint8_t>(joint.injected_driver_bits | (joint.enabled ? kEnabledBit : 0));
    // Idle draw plus a share of the motor current.
    info.bus_current_a = joint.enabled ? 0.1 + 0.2 * std::abs(joint.torque_nm / kNmPerAmp[i]) : 0.02;
    out.push_back(encode(info, options));
  }
}

}  // namespace robotd::piper::sim
