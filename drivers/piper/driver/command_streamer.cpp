#include "driver/command_streamer.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::piper {
namespace {

using driver::JointCommandKind;

constexpr std::int64_t kRefreshNs = 100'000'000;  // ModeCtrl, enable, e-stop and gripper repeats
constexpr double kGripperDeadbandM = 1e-5;        // 10 µm: below the gripper's resolution
constexpr double kEffortDeadbandNm = 1e-3;

bool any_arm_joint(const driver::CommandFrame& command, JointCommandKind kind) {
  const std::size_t count = std::min<std::size_t>(command.joint_count, kArmJoints);
  return std::any_of(command.joints.begin(), command.joints.begin() + static_cast<std::ptrdiff_t>(count),
                     [&](const driver::JointCommand& joint) { return joint.kind == kind; });
}

}  // namespace

void CommandStreamer::configure(const PiperParams& params, const CodecOptions& codec) {
  params_ = params;
  codec_ = codec;
  command_period_ns_ = static_cast<std::int64_t>(std::llround(1e9 / params.command_rate_hz));
  reset();
}

void CommandStreamer::reset() noexcept {
  estop_sent_ = false;
  want_enabled_ = params_.enable == EnablePolicy::kOnConnect;
  next_enable_ns_ = 0;
  next_estop_ns_ = 0;
  was_owned_ = false;
  mode_sent_ = StreamMode::kNone;
  next_mode_ns_ = 0;
  next_command_ns_ = 0;
  holding_.fill(false);
  gripper_sent_m_ = -1;
  gripper_effort_sent_ = -1;
  next_gripper_ns_ = 0;
}

void CommandStreamer::plan(const driver::CommandFrame& command, const ArmState& arm, bool hold_ops,
                           OutgoingFrames& out) noexcept {
  out.count = 0;
  const std::int64_t now_ns = command.tick_deadline_ns;
  plan_estop(command.estop, now_ns, out);
  if (command.estop) return;
  plan_enable(command, arm, now_ns, out);
  if (hold_ops && !was_owned_) return;
  plan_arm(command, arm, now_ns, out);
  if (params_.gripper) plan_gripper(command, arm, now_ns, out);
}

void CommandStreamer::plan_estop(bool estop, std::int64_t now_ns, OutgoingFrames& out) noexcept {
  if (estop) {
    if (!estop_sent_ || now_ns >= next_estop_ns_) {
      out.add(encode(MotionControl{.emergency_stop = EmergencyStop::kStop}, codec_));
      next_estop_ns_ = now_ns + kRefreshNs;
    }
    estop_sent_ = true;
    return;
  }
  if (!estop_sent_) return;
  // robotd's e-stop was reset: resume. The arm comes back disabled and in standby, so enable
  // and mode are sent again as after connect.
  out.add(encode(MotionControl{.emergency_stop = EmergencyStop::kResume}, codec_));
  estop_sent_ = false;
  want_enabled_ = params_.enable == EnablePolicy::kOnConnect || was_owned_;
  next_enable_ns_ = now_ns + kRefreshNs;  // give the resume its time before enabling
  mode_sent_ = StreamMode::kNone;
  holding_.fill(false);
}

void CommandStreamer::plan_enable(const driver::CommandFrame& command, const ArmState& arm, std::int64_t now_ns,
                                  OutgoingFrames& out) noexcept {
  const bool owned =
      std::any_of(command.joints.begin(), command.joints.begin() + static_cast<std::ptrdiff_t>(command.joint_count),
                  [](const driver::JointCommand& joint) { return joint.owned; });
  if (owned && !was_owned_ && params_.enable != EnablePolicy::kManual) want_enabled_ = true;
  if (!owned && was_owned_ && params_.disable_on_release) {
    out.add(encode(MotorEnable{.motor = kAllJoints, .enable = false}, codec_));
    if (params_.gripper) out.add(encode(GripperControl{.enable = GripperEnable::kDisable}, codec_));
    want_enabled_ = false;
  }
  was_owned_ = owned;
  if (!want_enabled_ || now_ns < next_enable_ns_) return;
  if (arm.all_enabled() && (!params_.gripper || (arm.gripper.status_bits & 0x40U) != 0)) {
    want_enabled_ = params_.enable == EnablePolicy::kOnConnect;  // keep re-enabling only by config
    return;
  }
  out.add(encode(MotorEnable{.motor = kAllJoints, .enable = true}, codec_));
  if (params_.gripper) {
    out.add(encode(
        GripperControl{
            .stroke_m = arm.gripper.stroke_m, .effort_nm = params_.gripper_effort_nm, .enable = GripperEnable::kEnable},
        codec_));
  }
  next_enable_ns_ = now_ns + kRefreshNs;
}

MitControl CommandStreamer::mit_command(int joint, const driver::JointCommand& command) const noexcept {
  const PiperJointParams& params = params_.joints[static_cast<std::size_t>(joint - 1)];
  MitControl mit{.joint = joint, .position_rad = command.position_rad, .velocity_rad_s = command.velocity_rad_s};
  if (command.kind == JointCommandKind::kImpedance) {
    mit.kp = command.kp;
    mit.kd = command.kd;
    mit.torque = command.torque_nm * params.mit_torque_scale;
  } else {  // a position target in MIT mode: the joint's default servo gains
    mit.kp = params.default_kp;
    mit.kd = params.default_kd;
  }
  return mit;
}

void CommandStreamer::plan_arm(const driver::CommandFrame& command, const ArmState& arm, std::int64_t now_ns,
                               OutgoingFrames& out) noexcept {
  const bool mit = any_arm_joint(command, JointCommandKind::kImpedance);
  if (!mit && !any_arm_joint(command, JointCommandKind::kPosition)) {
    mode_sent_ = StreamMode::kNone;
    holding_.fill(false);
    return;
  }
  if (now_ns < next_command_ns_) return;
  // Next group one period on; after a pause (or a late tick) start again from now.
  next_command_ns_ = std::max(next_command_ns_ + command_period_ns_, now_ns + command_period_ns_ / 2);

  const StreamMode mode = mit ? StreamMode::kMit : StreamMode::kJoint;
  if (mode != mode_sent_ || now_ns >= next_mode_ns_) {
    ModeControl control{.ctrl_mode = ControlMode::kCanCommand, .move_mode = MoveMode::kJ};
    if (mit) {
      control.move_mode = MoveMode::kMit;
      control.speed_percent = 0;
      control.mit = true;
    } else {
      control.speed_percent = static_cast<std::uint8_t>(params_.speed_percent);
      control.mit = params_.high_follow;
    }
    out.add(encode(control, codec_));
    mode_sent_ = mode;
    next_mode_ns_ = now_ns + kRefreshNs;
  }

  if (mit) {
    for (int j = 0; j < kArmJoints; ++j) {
      const driver::JointCommand& joint = command.joints[static_cast<std::size_t>(j)];
      if (joint.kind != JointCommandKind::kNone) out.add(encode(mit_command(j + 1, joint), codec_));
    }
    return;
  }
  std::array<double, kArmJoints> targets{};
  for (std::size_t j = 0; j < kArmJoints; ++j) {
    const driver::JointCommand& joint = command.joints[j];
    if (joint.kind == JointCommandKind::kPosition) {
      targets[j] = joint.position_rad;
      holding_[j] = false;
      continue;
    }
    if (!holding_[j]) {
      hold_rad_[j] = arm.joints[j].position_rad;
      holding_[j] = true;
    }
    targets[j] = hold_rad_[j];
  }
  for (const CanMessage& frame : encode_joint_targets(targets)) out.add(frame);
}

void CommandStreamer::plan_gripper(const driver::CommandFrame& command, const ArmState& arm, std::int64_t now_ns,
                                   OutgoingFrames& out) noexcept {
  if (command.joint_count <= kArmJoints) return;
  const driver::JointCommand& joint = command.joints[kArmJoints];
  if (joint.kind == JointCommandKind::kNone) return;
  const PiperJointParams& params = params_.gripper_joint;
  const double stroke = std::clamp(joint.position_rad, params.limits.position_min_rad, params.limits.position_max_rad);
  const double effort = joint.kind == JointCommandKind::kImpedance && joint.torque_nm > 0
                            ? std::min(joint.torque_nm, params.limits.effort_max_nm)
                            : params_.gripper_effort_nm;
  const bool changed = std::fabs(stroke - gripper_sent_m_) > kGripperDeadbandM ||
                       std::fabs(effort - gripper_effort_sent_) > kEffortDeadbandNm;
  if (!changed && now_ns < next_gripper_ns_) return;
  const bool enable = want_enabled_ || arm.all_enabled();
  out.add(encode(
      GripperControl{
          .stroke_m = stroke, .effort_nm = effort, .enable = enable ? GripperEnable::kEnable : GripperEnable::kDisable},
      codec_));
  gripper_sent_m_ = stroke;
  gripper_effort_sent_ = effort;
  next_gripper_ns_ = now_ns + kRefreshNs;
}

}  // namespace robotd::piper
