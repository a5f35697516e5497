#include "arm_model.hpp"

#include <algorithm>
#include <cmath>

#include "joint_dynamics.hpp"
#include "joint_profile.hpp"

namespace robotd::piper::sim {
namespace {

// Rigid-body stand-ins for MIT mode and for the feedback current: big joints J1–J3, wrist J4–J6.
constexpr std::array<double, kArmJoints> kInertiaKgM2 = {0.05, 0.05, 0.05, 0.01, 0.01, 0.01};
constexpr std::array<double, kArmJoints> kFrictionNmSRad = {0.2, 0.2, 0.2, 0.05, 0.05, 0.05};
constexpr std::array<double, kArmJoints> kEffortMaxNm = {40, 40, 40, 10, 10, 10};
// High-follow and MOVE L waypoint tracking: no speed-percent scaling and a stiffer ramp.
constexpr double kHighFollowAccelerationFactor = 4.0;
// Targets on the wire have 0.001° steps: a target at a limit may read a hair beyond it.
constexpr double kLimitToleranceRad = 1e-4;
constexpr double kAtTargetRad = 1e-9;
constexpr double kMovingRadS = 1e-3;  // MIT and e-stop: "moving" above this speed
constexpr double kGripperSpeedMS = 0.1;
constexpr std::uint8_t kAllMotorsAndGripper = 0xFF;

}  // namespace

std::array<JointSettings, kArmJoints> default_joint_settings() {
  // piper_sdk's table (spec §8.1), in rad.
  return {{{.min_rad = -2.6179, .max_rad = 2.6179},
           {.min_rad = 0.0, .max_rad = 3.14},
           {.min_rad = -2.967, .max_rad = 0.0},
           {.min_rad = -1.745, .max_rad = 1.745},
           {.min_rad = -1.22, .max_rad = 1.22},
           {.min_rad = -2.09439, .max_rad = 2.09439}}};
}

EndVelAcc default_end_limits() {
  EndVelAcc limits;
  limits.max_linear_velocity_m_s = 0.5;
  limits.max_angular_velocity_rad_s = 2.0;
  limits.max_linear_acceleration_m_s2 = 1.0;
  limits.max_angular_acceleration_rad_s2 = 4.0;
  return limits;
}

ArmModel::ArmModel(const std::array<double, kArmJoints>& initial_rad, DhVariant dh, MitLayout mit_layout)
    : dh_(dh), mit_layout_(mit_layout) {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    joints_[i].position_rad = initial_rad[i];
    joints_[i].target_rad = initial_rad[i];
  }
}

// --- host commands ------------------------------------------------------------------------------

void ArmModel::motion_control(const MotionControl& frame) {
  // Drag-teach is not simulated; the arm just reports the phase it was told.
  teach_status_ = frame.drag_teach_ctrl;
  if (frame.emergency_stop == EmergencyStop::kStop) {
    if (!estop_) cancel_motion();
    estop_ = true;
  } else if (frame.emergency_stop == EmergencyStop::kResume) {
    // The real arm drops here (motors de-powered at once); the simulator de-powers and holds.
    clear_errors();
    cancel_motion();
    estop_ = false;
    for (auto& joint : joints_) {
      joint.enabled = false;
      joint.velocity_rad_s = 0;
      joint.torque_nm = 0;
      joint.target_rad = joint.position_rad;
    }
    gripper_.enabled = false;
    gripper_.target_m = gripper_.stroke_m;
    ctrl_mode_ = ControlMode::kStandby;
    move_mode_ = MoveMode::kP;
    mit_flag_ = false;
    teach_status_ = 0;
  }
}

void ArmModel::mode_control(const ModeControl& frame) {
  if (estop_) return;
  const ControlMode previous_ctrl = ctrl_mode_;
  const MoveMode previous_move = move_mode_;
  const bool previous_mit = mit_flag_;
  ctrl_mode_ = frame.ctrl_mode;
  // pyAgxArm sends move mode 0xFF to change only the speed or the installation position.
  if (static_cast<std::uint8_t>(frame.move_mode) <= static_cast<std::uint8_t>(MoveMode::kCpv)) {
    move_mode_ = frame.move_mode;
  }
  // 0 % is taken literally: MOVE J, P and C do not progress (the spec gives no other meaning).
  speed_percent_ = std::min<int>(frame.speed_percent, 100);
  mit_flag_ = frame.mit;
  if (frame.installation != 0) installation_ = frame.installation;
  if (ctrl_mode_ != previous_ctrl || move_mode_ != previous_move || mit_flag_ != previous_mit) cancel_motion();
}

void ArmModel::joint_target(const JointTargetPair& frame) {
  if (!accepts_motion() || move_mode_ != MoveMode::kJ || frame.pair < 0 || frame.pair > 2) return;
  const std::array<double, 2> values = {frame.first_rad, frame.second_rad};
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::size_t index = static_cast<std::size_t>(frame.pair) * 2 + k;
    const JointSettings& limits = settings_.joints[index];
    SimJoint& joint = joints_[index];
    // Beyond a limit: arm status 0x04 and the joint's angle-limit bit, target clamped.
    joint.target_beyond_limit =
        values[k] < limits.min_rad - kLimitToleranceRad || values[k] > limits.max_rad + kLimitToleranceRad;
    joint.target_rad = std::clamp(values[k], limits.min_rad, limits.max_rad);
  }
  ik_failed_ = false;
}

void ArmModel::gripper_control(const GripperControl& frame) {
  if (estop_) return;
  // Gripper frames count in any control mode: the SDK demo enables the gripper before 0x151.
  gripper_.enabled = frame.enable == GripperEnable::kEnable || frame.enable == GripperEnable::kEnableClearError;
  if (frame.enable == GripperEnable::kDisableClearError || frame.enable == GripperEnable::kEnableClearError) {
    gripper_.injected_bits = 0;
  }
  gripper_.commanded_effort_nm = frame.effort_nm;
  if (frame.set_zero) {
    gripper_.stroke_m = 0;
    gripper_.homed = true;
  }
  gripper_.target_m = gripper_.enabled ? std::clamp(frame.stroke_m, 0.0, max_gripper_stroke_m()) : gripper_.stroke_m;
}

void ArmModel::mit_control(const MitControl& frame) {
  if (!accepts_motion() || !in_mit_mode() || frame.joint < 1 || frame.joint > kArmJoints) return;
  const std::size_t index = index_of(frame.joint);
  joints_[index].mit = MitCommand{.position_rad = frame.position_rad,
                                  .velocity_rad_s = frame.velocity_rad_s,
                                  .kp = frame.kp,
                                  .kd = frame.kd,
                                  .torque_nm = frame.torque * mit_torque_scale(index)};
}

void ArmModel::motor_enable(const MotorEnable& frame) {
  const bool all = frame.motor == kAllJoints || frame.motor == kAllMotorsAndGripper;
  for (int number = 1; number <= kArmJoints; ++number) {
    if (!all && frame.motor != number) continue;
    SimJoint& joint = joints_[index_of(number)];
    if (frame.enable != joint.enabled) {
      // Powering up holds where the joint is; old targets and MIT commands do not count.
      joint.target_rad = joint.position_rad;
      joint.velocity_rad_s = 0;
      joint.torque_nm = 0;
      joint.mit.reset();
    }
    joint.enabled = frame.enable;
  }
  if (frame.motor == kAllMotorsAndGripper) {  // the SDK msg docstring: 0xFF includes the gripper
    gripper_.enabled = frame.enable;
    gripper_.target_m = gripper_.stroke_m;
  }
}

bool ArmModel::joint_limit_set(const JointLimitSet& frame) {
  if (frame.joint < 1 || frame.joint > kArmJoints) return false;
  JointSettings updated = settings_.joints[index_of(frame.joint)];
  if (frame.max_angle_rad) updated.max_rad = *frame.max_angle_rad;
  if (frame.min_angle_rad) updated.min_rad = *frame.min_angle_rad;
  if (frame.max_speed_rad_s) updated.max_speed_rad_s = *frame.max_speed_rad_s;
  if (updated.min_rad > updated.max_rad) return false;  // refused: no ack
  settings_.joints[index_of(frame.joint)] = updated;
  SimJoint& joint = joints_[index_of(frame.joint)];
  joint.target_rad = std::clamp(joint.target_rad, updated.min_rad, updated.max_rad);
  return true;
}

std::optional<bool> ArmModel::joint_config(const JointConfig& frame) {
  const bool all = frame.joint == kAllJoints || frame.joint == kAllMotorsAndGripper;
  if (!all && (frame.joint < 1 || frame.joint > kArmJoints)) return std::nullopt;
  bool zero_set = false;
  for (int number = 1; number <= kArmJoints; ++number) {
    if (!all && frame.joint != number) continue;
    SimJoint& joint = joints_[index_of(number)];
    if (frame.apply_max_acc) settings_.joints[index_of(number)].max_acc_rad_s2 = frame.max_acc_rad_s2;
    if (frame.clear_error) {
      joint.injected_driver_bits = 0;
      joint.comm_error = false;
      joint.target_beyond_limit = false;
    }
    if (frame.set_zero) {  // the current position becomes 0
      joint.position_rad = 0;
      joint.velocity_rad_s = 0;
      joint.target_rad = 0;
      joint.mit.reset();
      zero_set = true;
    }
  }
  if (frame.clear_error) {
    injected_arm_status_.reset();
    ik_failed_ = false;
  }
  if (zero_set) cancel_motion();
  return zero_set;
}

void ArmModel::reset_settings(std::uint8_t setting) {
  if (setting == 1) settings_.end_limits = default_end_limits();
  if (setting == 2) settings_.joints = default_joint_settings();
}

// --- the control channel ------------------------------------------------------------------------

bool ArmModel::teleport(int joint, double position_rad) {
  if (joint < 1 || joint > kArmJoints) return false;
  const JointSettings& limits = settings_.joints[index_of(joint)];
  if (!(position_rad >= limits.min_rad - kLimitToleranceRad && position_rad <= limits.max_rad + kLimitToleranceRad)) {
    return false;
  }
  cancel_motion();
  SimJoint& target = joints_[index_of(joint)];
  target.position_rad = position_rad;
  target.velocity_rad_s = 0;
  target.target_rad = position_rad;
  return true;
}

bool ArmModel::place_gripper(double stroke_m) {
  if (!(stroke_m >= 0 && stroke_m <= max_gripper_stroke_m())) return false;
  gripper_.stroke_m = stroke_m;
  gripper_.target_m = stroke_m;
  gripper_.moving = false;
  return true;
}

void ArmModel::clear_errors() {
  injected_arm_status_.reset();
  ik_failed_ = false;
  for (auto& joint : joints_) {
    joint.injected_driver_bits = 0;
    joint.comm_error = false;
    joint.target_beyond_limit = false;
  }
  gripper_.injected_bits = 0;
}

// --- stopping -----------------------------------------------------------------------------------

void ArmModel::cancel_motion() {
  linear_move_.reset();
  waypoints_.clear();
  pose_parts_seen_ = 0;
  last_pose_target_.reset();
  received_pose_.reset();
  move_c_points_ = {};
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    SimJoint& joint = joints_[i];
    const JointSettings& limits = settings_.joints[i];
    joint.mit.reset();
    const double rest = stopping_position({joint.position_rad, joint.velocity_rad_s}, limits.max_acc_rad_s2);
    joint.target_rad =
        std::clamp(rest, std::min(limits.min_rad, joint.position_rad), std::max(limits.max_rad, joint.position_rad));
  }
}

// --- time ---------------------------------------------------------------------------------------

void ArmModel::step(double dt_s) {
  if (!(dt_s > 0)) return;
  step_planners(dt_s);
  for (std::size_t i = 0; i < joints_.size(); ++i) step_joint(i, dt_s);
  step_gripper(dt_s);
}

double ArmModel::mit_torque_scale(std::size_t index) const {
  // Firmware ≤ S-V1.8-7 executes 4× the wire torque on J1–J3 (spec §4.7); the 12-bit layout
  // carries N·m.
  if (mit_layout_ == MitLayout::kTorque12) return 1.0;
  return index < 3 ? 4.0 : 1.0;
}

void ArmModel::step_joint(std::size_t index, double dt_s) {
  SimJoint& joint = joints_[index];
  const JointSettings& limits = settings_.joints[index];
  const double previous_velocity = joint.velocity_rad_s;
  ProfileState state{.position_rad = joint.position_rad, .velocity_rad_s = joint.velocity_rad_s};
  if (estop_) {
    // Quick damped stop: brake to rest and hold there, powered or not. A joint never brakes past
    // its limits (the joint's own limit stops it), so nothing is left beyond one after resume.
    step_to_rest(limits.max_acc_rad_s2, dt_s, state);
    const double low = std::min(limits.min_rad, joint.position_rad);
    const double high = std::max(limits.max_rad, joint.position_rad);
    if (state.position_rad < low || state.position_rad > high) {
      state = ProfileState{.position_rad = std::clamp(state.position_rad, low, high), .velocity_rad_s = 0};
    }
    joint.target_rad = state.position_rad;
  } else if (!joint.enabled) {
    state.velocity_rad_s = 0;  // holds (the real arm sags under gravity)
  } else if (in_mit_mode()) {
    if (!joint.mit) {
      state.velocity_rad_s = 0;  // holds until its first MIT frame
    } else {
      // The last MIT command stays in force however old it is: the arm has no documented
      // command watchdog (spec §13 #10), so the simulator has none either.
      const MitCommand& command = *joint.mit;
      const ::robotd::sim::JointPhysics physics{.inertia_kg_m2 = kInertiaKgM2[index],
                                                .damping_nm_s_rad = kFrictionNmSRad[index],
                                                .position_min_rad = limits.min_rad,
                                                .position_max_rad = limits.max_rad,
                                                .effort_max_nm = kEffortMaxNm[index]};
      const ::robotd::sim::MotorLaw law{.kp = command.kp,
                                        .kd = command.kd,
                                        .position_rad = command.position_rad,
                                        .velocity_rad_s = command.velocity_rad_s,
                                        .torque_nm = command.torque_nm};
      ::robotd::sim::JointState dynamics{.position_rad = joint.position_rad, .velocity_rad_s = joint.velocity_rad_s};
      ::robotd::sim::step_joint(physics, law, 0.0, dt_s, dynamics);
      joint.position_rad = dynamics.position_rad;
      joint.velocity_rad_s = dynamics.velocity_rad_s;
      joint.torque_nm = dynamics.motor_torque_nm;
      joint.target_rad = command.position_rad;
      return;
    }
  } else {
    const bool fast = linear_move_.has_value() || (move_mode_ == MoveMode::kJ && mit_flag_);
    const ProfileLimits profile =
        fast ? ProfileLimits{.max_velocity_rad_s = limits.max_speed_rad_s,
                             .max_acceleration_rad_s2 = limits.max_acc_rad_s2 * kHighFollowAccelerationFactor}
             : ProfileLimits{.max_velocity_rad_s = limits.max_speed_rad_s * speed_percent_ / 100.0,
                             .max_acceleration_rad_s2 = limits.max_acc_rad_s2};
    step_toward(joint.target_rad, profile, dt_s, state);
  }
  joint.position_rad = state.position_rad;
  joint.velocity_rad_s = state.velocity_rad_s;
  // What the motor would need: inertia · acceleration + friction (no gravity model).
  joint.torque_nm = joint.enabled ? kInertiaKgM2[index] * (state.velocity_rad_s - previous_velocity) / dt_s +
                                        kFrictionNmSRad[index] * state.velocity_rad_s
                                  : 0.0;
}

void ArmModel::step_gripper(double dt_s) {
  if (estop_ || !gripper_.enabled) {
    gripper_.moving = false;
    gripper_.effort_nm = 0;
    if (!gripper_.enabled) gripper_.target_m = gripper_.stroke_m;
    return;
  }
  const double target = std::clamp(gripper_.target_m, 0.0, max_gripper_stroke_m());
  const double difference = target - gripper_.stroke_m;
  const double reach = kGripperSpeedMS * dt_s;
  gripper_.moving = std::abs(difference) > reach;
  gripper_.stroke_m = gripper_.moving ? gripper_.stroke_m + std::copysign(reach, difference) : target;
  // Nothing is modelled between the fingers: closing (or pressing shut) takes the commanded effort.
  const bool closing = (gripper_.moving && difference < 0) || (!gripper_.moving && target <= 0);
  gripper_.effort_nm = closing ? gripper_.commanded_effort_nm : 0.0;
}

// --- reports ------------------------------------------------------------------------------------

std::array<double, kArmJoints> ArmModel::positions() const {
  std::array<double, kArmJoints> out{};
  for (std::size_t i = 0; i < joints_.size(); ++i) out[i] = joints_[i].position_rad;
  return out;
}

bool ArmModel::joints_at_targets() const {
  return std::all_of(joints_.begin(), joints_.end(), [](const SimJoint& joint) {
    return !joint.enabled ||
           (std::abs(joint.target_rad - joint.position_rad) <= kAtTargetRad && joint.velocity_rad_s == 0);
  });
}

std::uint8_t ArmModel::arm_status() const {
  if (injected_arm_status_) return *injected_arm_status_;
  if (estop_) return 0x01;
  if (ik_failed_) return 0x02;
  if (angle_limit_bits() != 0) return 0x04;
  // A joint communication error shows in 0x2A1 byte 7 only; raise status 0x05 separately if wanted.
  return 0x00;
}

std::uint8_t ArmModel::motion_status() const {
  const auto moving = [](const SimJoint& joint) { return std::abs(joint.velocity_rad_s) > kMovingRadS; };
  if (estop_) return std::any_of(joints_.begin(), joints_.end(), moving) ? 1 : 0;
  if (linear_move_ || !waypoints_.empty()) return 1;
  if (in_mit_mode()) return std::any_of(joints_.begin(), joints_.end(), moving) ? 1 : 0;
  return joints_at_targets() ? 0 : 1;
}

std::uint8_t ArmModel::angle_limit_bits() const {
  unsigned bits = 0;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const SimJoint& joint = joints_[i];
    const JointSettings& limits = settings_.joints[i];
    const bool outside = joint.position_rad < limits.min_rad - kLimitToleranceRad ||
                         joint.position_rad > limits.max_rad + kLimitToleranceRad;
    if (joint.target_beyond_limit || outside) bits |= 1U << i;
  }
  return static_cast<std::uint8_t>(bits);
}

std::uint8_t ArmModel::comm_error_bits() const {
  unsigned bits = 0;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    if (joints_[i].comm_error) bits |= 1U << i;
  }
  return static_cast<std::uint8_t>(bits);
}

ArmStatus ArmModel::status_frame() const {
  ArmStatus status;
  status.ctrl_mode = ctrl_mode_;
  status.arm_status = arm_status();
  status.mode_feed = move_mode_;
  status.teach_status = teach_status_;
  status.motion_status = motion_status();
  status.angle_limit_bits = angle_limit_bits();
  status.comm_error_bits = comm_error_bits();
  return status;
}

double ArmModel::max_gripper_stroke_m() const { return settings_.gripper.max_range_mm / 1000.0; }

}  // namespace robotd::piper::sim
