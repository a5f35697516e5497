#include "board.hpp"

namespace robotd::parol6::sim {
namespace {

constexpr double kPassS = static_cast<double>(kPassNs) * 1e-9;
constexpr std::int64_t kMaxCatchUpNs = 100'000'000;
constexpr std::uint8_t kIoAlwaysSet = 0x07;

/// The free-running timer the firmware measures frame intervals with: 90 MHz / 128 =
/// 703 125 Hz = 9 ticks per 12 800 ns.
std::uint64_t timer_ticks(std::int64_t ns) { return static_cast<std::uint64_t>(ns) * 9U / 12'800U; }

std::array<std::int32_t, kJoints> initial_steps(const SimOptions& options) {
  if (options.initial_steps) return *options.initial_steps;
  if (options.homed) return kStandbySteps;
  return {};
}

}  // namespace

Board::Board(const SimOptions& options, std::int64_t start_ns)
    : start_ns_(start_ns), model_ns_(start_ns), arm_(options.homing_ms, initial_steps(options), options.homed) {
  if (options.gripper) gripper_.emplace();
}

void Board::run_until(std::int64_t now_ns) {
  if (now_ns - model_ns_ > kMaxCatchUpNs) model_ns_ = now_ns - kMaxCatchUpNs;
  while (model_ns_ + kPassNs <= now_ns) {
    arm_.step(kPassS);
    if (gripper_) gripper_->step(kPassS);
    model_ns_ += kPassNs;
  }
}

RobotFrame Board::answer(const HostFrame& frame, std::int64_t now_ns) {
  RobotFrame reply;
  const std::uint64_t ticks = timer_ticks(now_ns - start_ns_);
  timing_ticks_ = static_cast<std::uint16_t>((ticks - last_frame_ticks_) & 0xFFFFU);
  last_frame_ticks_ = ticks;
  reply.timing_ticks = timing_ticks_;
  // Sampled in the same pass, before the frame takes effect.
  for (std::size_t j = 0; j < arm_.joints().size(); ++j) {
    reply.position_steps[j] = static_cast<std::int32_t>(arm_.joints()[j].steps);
    reply.speed_steps_s[j] = arm_.joints()[j].speed_steps_s;
  }
  reply.homed = homed_byte(arm_.homed_mask());

  arm_.apply(frame);
  outputs_ = static_cast<std::uint8_t>(frame.io & (io::kOut1 | io::kOut2));
  reply.io = io_byte();
  reply.temperature_error = 0x03;  // never set by this firmware
  reply.position_error = 0x03;     // never set by this firmware
  reply.timeout_error = 100;       // constant
  reply.echoed_command = frame.command;
  // Gripper: id, speed and object detection are constants; the rest is the answer to the
  // previous cycle's CAN message (0 / 2 / 1 before the first).
  reply.gripper_id = 0;
  reply.gripper_speed = 1;
  reply.object_detection = 1;
  if (last_answer_) {
    reply.gripper_position = last_answer_->position;
    reply.gripper_current = last_answer_->current_ma;
    reply.gripper_status = last_answer_->status;
  } else {
    reply.gripper_position = 0;
    reply.gripper_current = 2;
    reply.gripper_status = 1;
  }
  reply.crc = kRobotCrcPlaceholder;
  exchange_with_gripper(frame);
  return reply;
}

void Board::exchange_with_gripper(const HostFrame& frame) {
  const GripperFields fields{.position = frame.gripper_position,
                             .speed = frame.gripper_speed,
                             .current = frame.gripper_current_ma,
                             .command = frame.gripper_command,
                             .id = frame.gripper_id};
  const bool unchanged = fields == previous_gripper_fields_;
  previous_gripper_fields_ = fields;
  // The message goes to node `id`; the board takes an answer only from that node.
  if (!gripper_ || frame.gripper_id != Ssg48Gripper::kNodeId) return;
  if (frame.gripper_mode == static_cast<std::uint8_t>(GripperMode::kCalibrate)) {
    gripper_->calibrate();
  } else if (frame.gripper_mode == static_cast<std::uint8_t>(GripperMode::kClearError)) {
    gripper_->clear_error();
  } else if (unchanged) {
    last_answer_ = gripper_->answer();  // empty data pack: a poll
  } else {
    // Only the low bytes of position and speed go on the bus.
    last_answer_ = gripper_->data_pack(static_cast<std::uint8_t>(frame.gripper_position & 0xFF),
                                       static_cast<std::uint8_t>(frame.gripper_speed & 0xFF), frame.gripper_current_ma,
                                       frame.gripper_command);
  }
}

std::uint8_t Board::io_byte() const {
  unsigned byte = kIoAlwaysSet | outputs_;
  if (in1_) byte |= io::kIn1;
  if (in2_) byte |= io::kIn2;
  if (!estop_pressed_) byte |= io::kEstopReleased;
  return static_cast<std::uint8_t>(byte);
}

}  // namespace robotd::parol6::sim
