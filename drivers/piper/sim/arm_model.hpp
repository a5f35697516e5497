// The simulated PiPER: six joints and a gripper behind the main controller, with the state the
// arm reports (status, modes, errors) and the physics the simulator steps at 1 kHz. No I/O:
// the controller feeds it decoded frames, the feedback reads it, the control channel pokes it.
//
// What it models (docs/drivers/piper.md, piper_can.md):
//   - motors power up disabled; a disabled joint holds where it is (the real arm sags);
//   - motion commands count only in CAN command mode (0x151 byte 0 = 0x01), as on the arm;
//   - MOVE J: rate-limited moves to the targets at speed_percent % of the joint's max speed and
//     at its max acceleration; high-follow (0xAD) tracks without the speed-percent scaling;
//   - MIT: torque = kp·(p − q) + kd·(v − dq) + t·scale on a rigid joint with viscous friction;
//   - MOVE P / L / C through the kinematics' IK (no solution: arm status 0x02, no motion);
//   - the emergency stop brakes every joint to rest and holds; resume de-powers and resets.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "codec/piper_frames.hpp"
#include "kinematics/piper_kinematics.hpp"
#include "linear_move.hpp"

namespace robotd::piper::sim {

inline constexpr double kStepS = 1e-3;  // physics step

/// 0x473/0x47C/0x474/0x475 values of one joint.
struct JointSettings {
  double min_rad = 0;
  double max_rad = 0;
  double max_speed_rad_s = 3.0;
  double max_acc_rad_s2 = 5.0;
};

/// The SDK joint limits (spec §8.1), 3 rad/s, 5 rad/s².
std::array<JointSettings, kArmJoints> default_joint_settings();

/// End-effector limits (0x478): not published anywhere; values of the right magnitude.
EndVelAcc default_end_limits();

/// Values the arm stores and reports on request (0x47x).
struct ArmSettings {
  std::array<JointSettings, kArmJoints> joints = default_joint_settings();
  EndVelAcc end_limits = default_end_limits();
  std::array<std::uint8_t, kArmJoints> collision_levels{};  // 0x47A / 0x47B
  GripperParams gripper;                                    // 0x47D / 0x47E
  std::uint8_t payload = 0;                                 // 0x477 byte 4
  std::uint8_t feedback_48x = 0;                            // 0x477 byte 2 (stored, never sent)
  MasterSlaveConfig master_slave;                           // 0x470 (stored, not simulated)
};

struct MitCommand {
  double position_rad = 0;
  double velocity_rad_s = 0;
  double kp = 0;
  double kd = 0;
  double torque_nm = 0;  // after the firmware's scale
};

struct SimJoint {
  double position_rad = 0;
  double velocity_rad_s = 0;
  double torque_nm = 0;  // what the motor applied in the last step (feedback current)
  double target_rad = 0;
  bool enabled = false;
  bool target_beyond_limit = false;  // the last target was outside the limits (clamped)
  std::optional<MitCommand> mit;     // the last MIT frame in MIT mode
  // Faults raised through the control channel.
  std::uint8_t injected_driver_bits = 0;
  bool comm_error = false;
};

struct SimGripper {
  double stroke_m = 0;
  double target_m = 0;
  double commanded_effort_nm = 0;
  double effort_nm = 0;
  bool enabled = false;
  bool moving = false;
  bool homed = true;
  std::uint8_t injected_bits = 0;
};

class ArmModel {
 public:
  ArmModel(const std::array<double, kArmJoints>& initial_rad, DhVariant dh, MitLayout mit_layout);

  // --- host commands (decoded frames) -------------------------------------------------------
  void motion_control(const MotionControl& frame);  // 0x150
  void mode_control(const ModeControl& frame);      // 0x151
  void end_pose_target(const EndPoseTargetPart& frame);
  void joint_target(const JointTargetPair& frame);
  void move_c_point(const MoveCPoint& frame);
  void gripper_control(const GripperControl& frame);
  void mit_control(const MitControl& frame);
  void motor_enable(const MotorEnable& frame);
  /// 0x474: false if the joint number is not 1–6 (no ack then).
  bool joint_limit_set(const JointLimitSet& frame);
  /// 0x475: nullopt if the joint number is invalid; else whether a zero was set.
  std::optional<bool> joint_config(const JointConfig& frame);
  /// 0x477 byte 1: 1 resets the end-effector limits, 2 the joint limits, speeds and accs.
  void reset_settings(std::uint8_t setting);
  ArmSettings& settings() { return settings_; }
  const ArmSettings& settings() const { return settings_; }

  // --- the control channel ------------------------------------------------------------------
  /// Puts joint `joint` (1–6) at `position_rad` at rest; false if outside its limits.
  bool teleport(int joint, double position_rad);
  /// Puts the gripper at `stroke_m` at rest; false if outside 0 … its max stroke.
  bool place_gripper(double stroke_m);
  void inject_arm_status(std::uint8_t code) { injected_arm_status_ = code; }
  void inject_driver_bits(int joint, std::uint8_t bits) { joints_.at(index_of(joint)).injected_driver_bits = bits; }
  void inject_comm_error(int joint, bool error) { joints_.at(index_of(joint)).comm_error = error; }
  void inject_gripper_bits(std::uint8_t bits) { gripper_.injected_bits = bits; }
  /// Clears every injected fault and the error state (what 0x150 resume clears, without it).
  void clear_errors();

  // --- time ---------------------------------------------------------------------------------
  void step(double dt_s);

  // --- what the arm reports -----------------------------------------------------------------
  const std::array<SimJoint, kArmJoints>& joints() const { return joints_; }
  const SimGripper& gripper() const { return gripper_; }
  std::array<double, kArmJoints> positions() const;
  CartesianPose end_pose() const { return forward_kinematics(positions(), dh_); }
  ControlMode ctrl_mode() const { return ctrl_mode_; }
  MoveMode move_mode() const { return move_mode_; }
  bool mit() const { return mit_flag_; }
  int speed_percent() const { return speed_percent_; }
  std::uint8_t installation() const { return installation_; }
  std::uint8_t teach_status() const { return teach_status_; }
  bool estop() const { return estop_; }
  std::uint8_t arm_status() const;
  std::uint8_t motion_status() const;
  std::uint8_t angle_limit_bits() const;
  std::uint8_t comm_error_bits() const;
  ArmStatus status_frame() const;
  double max_gripper_stroke_m() const;

 private:
  static std::size_t index_of(int joint) { return static_cast<std::size_t>(joint - 1); }
  bool accepts_motion() const { return !estop_ && ctrl_mode_ == ControlMode::kCanCommand; }
  bool in_mit_mode() const { return move_mode_ == MoveMode::kMit && mit_flag_; }
  /// Stops every planned motion: each joint brakes to rest from where it is.
  void cancel_motion();
  void start_pose_move(const CartesianPose& pose);
  void start_move_c();
  /// IK from `seed`; sets the "no IK solution" status and returns nullopt when it fails.
  std::optional<std::array<double, kArmJoints>> solve(const CartesianPose& pose,
                                                      const std::array<double, kArmJoints>& seed);
  void set_targets(const std::array<double, kArmJoints>& targets_rad);
  double mit_torque_scale(std::size_t index) const;
  void step_joint(std::size_t index, double dt_s);
  void step_planners(double dt_s);
  void step_gripper(double dt_s);
  bool joints_at_targets() const;

  DhVariant dh_;
  MitLayout mit_layout_;
  ArmSettings settings_;
  std::array<SimJoint, kArmJoints> joints_{};
  SimGripper gripper_;

  ControlMode ctrl_mode_ = ControlMode::kStandby;
  MoveMode move_mode_ = MoveMode::kP;
  bool mit_flag_ = false;
  int speed_percent_ = 100;
  std::uint8_t installation_ = 1;
  std::uint8_t teach_status_ = 0;
  bool estop_ = false;
  bool ik_failed_ = false;
  std::optional<std::uint8_t> injected_arm_status_;

  // MOVE P / L / C.
  std::array<double, 6> pose_parts_{};             // x, y, z, rx, ry, rz as the 0x152–0x154 frames arrive
  std::uint8_t pose_parts_seen_ = 0;               // bit per frame since the last complete pose
  std::optional<CartesianPose> last_pose_target_;  // P / L: a repeated target does not restart
  std::optional<CartesianPose> received_pose_;     // C: the pose the next 0x158 names
  std::array<std::optional<CartesianPose>, 3> move_c_points_;
  std::optional<LinearMove> linear_move_;
  double linear_ik_due_s_ = 0;
  std::vector<std::array<double, kArmJoints>> waypoints_;  // MOVE C: joint targets still to reach
};

}  // namespace robotd::piper::sim
