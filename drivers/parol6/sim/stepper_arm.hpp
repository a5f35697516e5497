// The firmware's joint side (spec §6, §9): the command in force, the disabled flag, the six
// steppers and the homing state machine. apply() is what a valid frame changes; step() is one
// pass of the firmware's main loop, where the command in force is carried out (the last
// command stays in force until the next valid frame; there is no watchdog).
#pragma once

#include <array>
#include <cstdint>

#include "codec/parol6_frames.hpp"
#include "homing_sequence.hpp"
#include "stepper_joint.hpp"

namespace robotd::parol6::sim {

class StepperArm {
 public:
  /// Power-up: command 0, enabled, counters at `initial_steps`; `homed` marks every joint homed.
  StepperArm(std::int64_t homing_ms, const std::array<std::int32_t, kJoints>& initial_steps, bool homed);

  /// A valid frame's command and set points take effect.
  void apply(const HostFrame& frame);
  /// One main-loop pass of `dt_s`: 123 runs every joint at its speed; 156 recomputes each
  /// speed from the position error, ((P_cmd − P) / 0.01 + V_cmd) / 2, and runs; 100 and 255
  /// advance a homing in progress; nothing moves while disabled or under any other command.
  void step(double dt_s);

  /// Overwrites joint `joint`'s (0 … 5) counter, as the control channel's set_steps does.
  void set_steps(int joint, std::int64_t steps);

  const Steppers& joints() const { return joints_; }
  std::uint8_t command() const { return command_; }
  bool disabled() const { return disabled_; }
  std::uint8_t homed_mask() const { return homed_mask_; }  // bit j = joint j
  const HomingSequence& homing() const { return homing_; }
  const std::array<std::int32_t, kJoints>& position_command() const { return position_command_; }
  const std::array<std::int32_t, kJoints>& speed_command() const { return speed_command_; }

 private:
  Steppers joints_{};
  std::array<std::int32_t, kJoints> position_command_{};
  std::array<std::int32_t, kJoints> speed_command_{};
  std::uint8_t command_ = command::kNone;
  bool disabled_ = false;
  std::uint8_t homed_mask_ = 0;
  HomingSequence homing_;
};

/// The reply's homed byte: element j (J1 … J6) at bit 7 − j, the two spare bits always 1.
std::uint8_t homed_byte(std::uint8_t homed_mask);

}  // namespace robotd::parol6::sim
