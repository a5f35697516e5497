#include "stepper_arm.hpp"

namespace robotd::parol6::sim {
namespace {

// 156: speed = ((P_cmd − P_actual) / 0.01 + V_cmd) / 2, truncated to an integer.
constexpr std::int64_t kInversePeriod = 100;  // 1 / 0.01 s

}  // namespace

StepperArm::StepperArm(std::int64_t homing_ms, const std::array<std::int32_t, kJoints>& initial_steps, bool homed)
    : homed_mask_(homed ? kAllJointsMask : 0), homing_(homing_ms) {
  for (std::size_t j = 0; j < joints_.size(); ++j) joints_[j].set_position(initial_steps[j]);
}

void StepperArm::apply(const HostFrame& frame) {
  command_ = frame.command;
  position_command_ = frame.position_steps;
  speed_command_ = frame.speed_steps_s;
  switch (command_) {
    case command::kJog:
      if (disabled_) break;
      homing_.abort();
      for (std::size_t j = 0; j < joints_.size(); ++j) joints_[j].set_speed(speed_command_[j]);
      break;
    case command::kGoToPosition:
      if (!disabled_) homing_.abort();  // the speeds follow in step()
      break;
    case command::kHome:
      if (!disabled_ && !homing_.active()) homing_.start(joints_, homed_mask_);  // again after a finished one
      break;
    case command::kEnable:
      disabled_ = false;
      homing_.abort();
      break;
    case command::kDisable:
      disabled_ = true;
      homing_.abort();
      break;
    case command::kClearError:
      homing_.abort();
      break;
    case command::kIdle:  // the speed set point is stored (and reported) but not run
      for (std::size_t j = 0; j < joints_.size(); ++j) joints_[j].set_speed(speed_command_[j]);
      break;
    default:  // 0, 69 (demo: not simulated) and unknown codes: nothing
      break;
  }
}

void StepperArm::step(double dt_s) {
  if (disabled_) return;  // the drivers are not stepped (they stay energised)
  switch (command_) {
    case command::kJog:
      for (StepperJoint& joint : joints_) joint.run(dt_s);
      break;
    case command::kGoToPosition:
      for (std::size_t j = 0; j < joints_.size(); ++j) {
        StepperJoint& joint = joints_[j];
        const std::int64_t error = position_command_[j] - joint.steps;
        joint.set_speed((error * kInversePeriod + speed_command_[j]) / 2);
        joint.run(dt_s);
      }
      break;
    case command::kHome:
    case command::kIdle:
      homing_.step(dt_s, joints_, homed_mask_);
      break;
    default:
      break;
  }
}

void StepperArm::set_steps(int joint, std::int64_t steps) {
  joints_.at(static_cast<std::size_t>(joint)).set_position(steps);
}

std::uint8_t homed_byte(std::uint8_t homed_mask) {
  unsigned byte = 0x03;
  for (int j = 0; j < kJoints; ++j) {
    if ((homed_mask & (1U << static_cast<unsigned>(j))) != 0) byte |= 0x80U >> static_cast<unsigned>(j);
  }
  return static_cast<std::uint8_t>(byte);
}

}  // namespace robotd::parol6::sim
