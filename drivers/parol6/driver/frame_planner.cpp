#include "driver/frame_planner.hpp"

#include <algorithm>

#include "codec/joint_units.hpp"

namespace robotd::parol6 {
namespace {

using driver::JointCommandKind;

constexpr int kHomeFrames = 10;  // like the API: HOME for 10 frames, then IDLE lets it run

bool any_owned(const driver::CommandFrame& command) {
  const std::size_t count = std::min<std::size_t>(command.joint_count, kJoints);
  return std::any_of(command.joints.begin(), command.joints.begin() + static_cast<std::ptrdiff_t>(count),
                     [](const driver::JointCommand& joint) { return joint.owned; });
}

std::uint8_t one_shot_command(OneShot one_shot) {
  switch (one_shot) {
    case OneShot::kHome:
      return command::kHome;
    case OneShot::kEnable:
      return command::kEnable;
    case OneShot::kDisable:
      return command::kDisable;
    case OneShot::kClearError:
      return command::kClearError;
    case OneShot::kNone:
      break;
  }
  return command::kIdle;
}

}  // namespace

void FramePlanner::reset() {
  estop_sent_ = false;
  homing_frames_left_ = 0;
  streaming_session_ = false;
  have_previous_.fill(false);
  holding_.fill(false);
}

HostFrame FramePlanner::base_frame(const PlannerInput& input) const {
  HostFrame frame;
  frame.command = command::kIdle;
  const Peripherals& p = input.peripherals;
  frame.io = static_cast<std::uint8_t>((p.out1 ? io::kOut1 : 0) | (p.out2 ? io::kOut2 : 0));
  frame.gripper_position = p.gripper_position;
  frame.gripper_speed = p.gripper_speed;
  frame.gripper_current_ma = p.gripper_current_ma;
  frame.gripper_command = p.gripper_command;
  frame.gripper_mode = p.gripper_mode;
  frame.gripper_id = p.gripper_id;
  // IDLE and DISABLE carry the measured positions and zero speeds, like the commander's dummy.
  if (input.board != nullptr) frame.position_steps = input.board->position_steps;
  return frame;
}

HostFrame FramePlanner::plan(const PlannerInput& input) {
  HostFrame frame = base_frame(input);
  const driver::CommandFrame& command = *input.command;
  const bool board_estop = input.board != nullptr && input.board->estop_pressed();
  streaming_session_ = false;

  if (command.estop || board_estop) {
    frame.command = command::kDisable;
    frame.gripper_command = static_cast<std::uint8_t>(frame.gripper_command | gripper_command::kEstop);
    estop_sent_ = true;
    homing_frames_left_ = 0;
    have_previous_.fill(false);
    holding_.fill(false);
    return frame;
  }
  if (estop_sent_) {  // reset: the board stays disabled until told otherwise
    estop_sent_ = false;
    frame.command = command::kEnable;
    return frame;
  }
  if (input.one_shot != OneShot::kNone) {
    frame.command = one_shot_command(input.one_shot);
    homing_frames_left_ = input.one_shot == OneShot::kHome ? kHomeFrames - 1 : 0;
    return frame;
  }
  if (homing_frames_left_ > 0) {
    --homing_frames_left_;
    frame.command = command::kHome;
    return frame;
  }
  if (input.trajectory != nullptr) {
    frame.command = command::kGoToPosition;
    frame.position_steps = input.trajectory->position_steps;
    frame.speed_steps_s = input.trajectory->speed_steps_s;
    have_previous_.fill(false);
    return frame;
  }
  if (input.board != nullptr && input.board->all_homed() && any_owned(command)) {
    plan_session(command, *input.board, frame);
    return frame;
  }
  have_previous_.fill(false);
  holding_.fill(false);
  return frame;  // IDLE
}

void FramePlanner::plan_session(const driver::CommandFrame& command, const RobotFrame& board, HostFrame& frame) {
  frame.command = command::kGoToPosition;
  streaming_session_ = true;
  for (int j = 0; j < kJoints; ++j) {
    const auto index = static_cast<std::size_t>(j);
    const driver::JointCommand& joint = command.joints[index];
    if (joint.kind != JointCommandKind::kPosition) {
      // Not driven by anyone: hold where the stream found it.
      if (!holding_[index]) {
        hold_steps_[index] = board.position_steps[index];
        holding_[index] = true;
      }
      have_previous_[index] = false;
      frame.position_steps[index] = hold_steps_[index];
      frame.speed_steps_s[index] = 0;
      continue;
    }
    holding_[index] = false;
    const double velocity =
        have_previous_[index] ? (joint.position_rad - previous_target_rad_[index]) / period_s_ : 0.0;
    previous_target_rad_[index] = joint.position_rad;
    have_previous_[index] = true;
    frame.position_steps[index] = rad_to_steps(j, joint.position_rad + velocity * period_s_);
    frame.speed_steps_s[index] = rad_per_s_to_steps_per_s(j, velocity);
  }
}

}  // namespace robotd::parol6
