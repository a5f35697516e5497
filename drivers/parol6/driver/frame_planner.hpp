// What the driver sends the board in one exchange (every 1/exchange_rate_hz), on the RT thread.
// The board keeps executing the last command until the next frame and has no watchdog, so
// every frame is one that is safe to be the last:
//   - e-stop (robotd's, or the board's E-stop input pressed): DISABLE (102) every frame, as the
//     commander does; on reset one ENABLE (101), then idle;
//   - a one-shot request from an op: HOME (100 for 10 frames, then idle while it runs), ENABLE,
//     DISABLE or CLEAR ERROR (one frame);
//   - a trajectory from an op (move_pose, move_cart, jog): GO TO POSITION (156) with its samples;
//   - a session owning joints (once homed): GO TO POSITION with the newest targets, one period
//     ahead, and their velocity as the speed field, so the board's tracker
//     v = ((P − p)/0.01 + V)/2 reaches each target at the next frame instead of lagging it;
//   - otherwise IDLE (255): no motion (homing, if running, continues). Never JOG (123): a jog
//     frame left as the last one would turn the motors forever.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "codec/parol6_frames.hpp"
#include "robotd/driver/types.hpp"

namespace robotd::parol6 {

enum class OneShot : std::uint8_t { kNone, kHome, kEnable, kDisable, kClearError };

/// A trajectory sample (an op's move) in microsteps and microsteps/s.
struct StepTarget {
  std::array<std::int32_t, kJoints> position_steps{};
  std::array<std::int32_t, kJoints> speed_steps_s{};
};

/// The gripper and output fields, set by ops, sent in every frame.
struct Peripherals {
  bool out1 = false;
  bool out2 = false;
  std::int16_t gripper_position = 0;
  std::int16_t gripper_speed = 0;
  std::int16_t gripper_current_ma = 0;
  std::uint8_t gripper_command = 0;
  std::uint8_t gripper_mode = 0;  // calibrate / clear error: the driver sends it for one frame
  std::uint8_t gripper_id = 0;
};

struct PlannerInput {
  const driver::CommandFrame* command = nullptr;  // robotd's newest
  const RobotFrame* board = nullptr;              // the newest reply (nullptr before the first)
  OneShot one_shot = OneShot::kNone;              // consumed by this frame
  const StepTarget* trajectory = nullptr;         // the op move's next sample, if one runs
  Peripherals peripherals;
};

class FramePlanner {
 public:
  explicit FramePlanner(double period_s = 0.01) : period_s_(period_s) {}
  void set_period(double period_s) { period_s_ = period_s; }
  /// After (re)connecting: no e-stop sent, no homing in progress, no previous targets.
  void reset();

  HostFrame plan(const PlannerInput& input);

  bool homing() const { return homing_frames_left_ > 0; }
  /// Whether the last plan() streamed a session's targets.
  bool streaming_session() const { return streaming_session_; }

 private:
  HostFrame base_frame(const PlannerInput& input) const;
  void plan_session(const driver::CommandFrame& command, const RobotFrame& board, HostFrame& frame);

  double period_s_;
  bool estop_sent_ = false;
  int homing_frames_left_ = 0;
  bool streaming_session_ = false;
  std::array<bool, kJoints> have_previous_{};
  std::array<double, kJoints> previous_target_rad_{};
  std::array<bool, kJoints> holding_{};
  std::array<std::int32_t, kJoints> hold_steps_{};
};

}  // namespace robotd::parol6
