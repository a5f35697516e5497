// The control board: the firmware's main loop between frames (run_until: passes of 100 µs, in
// which the command in force is carried out and the gripper moves) and its handling of one
// valid frame (answer: spec §5's order — measure the timing, sample the joints, decode, read
// the inputs and drive the outputs, one CAN exchange with the gripper, build the reply).
#pragma once

#include <cstdint>
#include <optional>

#include "codec/parol6_frames.hpp"
#include "sim_options.hpp"
#include "ssg48_gripper.hpp"
#include "stepper_arm.hpp"

namespace robotd::parol6::sim {

inline constexpr std::int64_t kPassNs = 100'000;  // 10 kHz main loop

class Board {
 public:
  Board(const SimOptions& options, std::int64_t start_ns);

  /// Runs the main loop up to `now_ns`. Behind by more than 100 ms (the process was
  /// descheduled): the board loses that time instead of catching up in one burst.
  void run_until(std::int64_t now_ns);
  /// One valid frame, received at `now_ns`, and its reply.
  RobotFrame answer(const HostFrame& frame, std::int64_t now_ns);

  StepperArm& arm() { return arm_; }
  const StepperArm& arm() const { return arm_; }
  /// nullptr when no gripper is on the bus (--no-gripper).
  Ssg48Gripper* gripper() { return gripper_ ? &*gripper_ : nullptr; }
  const Ssg48Gripper* gripper() const { return gripper_ ? &*gripper_ : nullptr; }
  /// The gripper's last answer, which the next reply carries; nullopt before the first.
  const std::optional<GripperAnswer>& last_gripper_answer() const { return last_answer_; }

  void set_estop_pressed(bool pressed) { estop_pressed_ = pressed; }
  void set_in1(bool level) { in1_ = level; }
  void set_in2(bool level) { in2_ = level; }
  bool estop_pressed() const { return estop_pressed_; }
  bool in1() const { return in1_; }
  bool in2() const { return in2_; }
  std::uint8_t outputs() const { return outputs_; }  // io::kOut1 | io::kOut2 as last commanded
  std::uint8_t io_byte() const;
  std::uint16_t timing_ticks() const { return timing_ticks_; }

 private:
  struct GripperFields {
    std::int16_t position = 0;
    std::int16_t speed = 0;
    std::int16_t current = 0;
    std::uint8_t command = 0;
    std::uint8_t id = 0;
    bool operator==(const GripperFields&) const = default;
  };
  void exchange_with_gripper(const HostFrame& frame);

  std::int64_t start_ns_;
  std::int64_t model_ns_;
  StepperArm arm_;
  std::optional<Ssg48Gripper> gripper_;
  std::optional<GripperAnswer> last_answer_;
  GripperFields previous_gripper_fields_;
  std::uint64_t last_frame_ticks_ = 0;
  std::uint16_t timing_ticks_ = 0;
  bool estop_pressed_ = false;
  bool in1_ = false;
  bool in2_ = false;
  std::uint8_t outputs_ = 0;
};

}  // namespace robotd::parol6::sim
