// Turns robotd's per-tick CommandFrame into PiPER control frames, on the RT thread:
//   - joint streaming at command_rate_hz (the loop runs faster; the newest targets go out):
//     JointCtrl 0x155–0x157 after ModeCtrl "CAN, MOVE J, speed %" while every driven joint has
//     a position target, MIT 0x15A–0x15F after ModeCtrl "CAN, MIT" while any joint has an
//     impedance command (TORQUE / MIXED sessions, DAMPING and ZERO_TORQUE behaviours);
//   - ModeCtrl again whenever the mode changes and every 100 ms, so an arm that fell back to
//     standby (after a reset or the teach button) takes commands again;
//   - enable (0x471) when a session first owns a joint (or at connect, by config), repeated
//     every 100 ms until the six enable bits are set; disable on the last release if configured;
//   - the gripper (0x159) when its target changes, and every 100 ms;
//   - robotd's e-stop as EmergencyStop 0x150 "stop" (repeated every 100 ms), its reset as
//     0x150 "resume", after which the arm is disabled and re-enabled like at connect.
// Joints with no command hold where they were measured when the stream began.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "codec/piper_frames.hpp"
#include "driver/arm_state.hpp"
#include "driver/piper_params.hpp"
#include "robotd/driver/types.hpp"

namespace robotd::piper {

struct OutgoingFrames {
  static constexpr std::size_t kCapacity = 16;
  std::array<CanMessage, kCapacity> frames{};
  std::size_t count = 0;

  void add(const CanMessage& message) noexcept {
    if (count < kCapacity) frames[count++] = message;
  }
};

class CommandStreamer {
 public:
  /// Non-RT: before the first plan() and after every configure().
  void configure(const PiperParams& params, const CodecOptions& codec);
  /// After connect() / recover(): nothing sent yet, nothing assumed about the arm.
  void reset() noexcept;

  /// The frames to send for this tick. `hold_ops`: a device_call motion op (end_pose, move_c,
  /// mode, gripper) drives the arm, so streaming waits until a session owns a joint again.
  void plan(const driver::CommandFrame& command, const ArmState& arm, bool hold_ops, OutgoingFrames& out) noexcept;

  /// Whether a session owned a joint at the last plan(): motion ops are refused then, and a
  /// session that takes a joint ends a motion op's hold.
  bool any_owned() const noexcept { return was_owned_; }

 private:
  enum class StreamMode : std::uint8_t { kNone, kJoint, kMit };

  void plan_estop(bool estop, std::int64_t now_ns, OutgoingFrames& out) noexcept;
  void plan_enable(const driver::CommandFrame& command, const ArmState& arm, std::int64_t now_ns,
                   OutgoingFrames& out) noexcept;
  void plan_arm(const driver::CommandFrame& command, const ArmState& arm, std::int64_t now_ns,
                OutgoingFrames& out) noexcept;
  void plan_gripper(const driver::CommandFrame& command, const ArmState& arm, std::int64_t now_ns,
                    OutgoingFrames& out) noexcept;
  MitControl mit_command(int joint, const driver::JointCommand& command) const noexcept;

  PiperParams params_;
  CodecOptions codec_;
  std::int64_t command_period_ns_ = 5'000'000;

  bool estop_sent_ = false;
  std::int64_t next_estop_ns_ = 0;
  bool want_enabled_ = false;
  std::int64_t next_enable_ns_ = 0;
  bool was_owned_ = false;
  StreamMode mode_sent_ = StreamMode::kNone;
  std::int64_t next_mode_ns_ = 0;
  std::int64_t next_command_ns_ = 0;
  std::array<bool, kArmJoints> holding_{};
  std::array<double, kArmJoints> hold_rad_{};
  double gripper_sent_m_ = -1;
  double gripper_effort_sent_ = -1;
  std::int64_t next_gripper_ns_ = 0;
};

}  // namespace robotd::piper
