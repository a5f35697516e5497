// The unsolicited motion-feedback frames of the command port (§2.5): register byte 0xFF, then a
// status byte, type, original register, task id, code and controller time.
#include <cstddef>
#include <cstdint>
#include <string>

#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

constexpr std::uint8_t kFeedbackRegister = static_cast<std::uint8_t>(Register::kMotionFeedback);
// Status, type, register, task id (2), code, time (8): frame offsets 7..20.
constexpr std::size_t kFeedbackBodyBytes = 14;

}  // namespace

bool is_motion_feedback(const Frame& frame) { return frame.reg == kFeedbackRegister; }

Result<MotionFeedback> parse_motion_feedback(const Frame& frame) {
  if (!is_motion_feedback(frame)) {
    return make_error(ErrorCode::kInvalidArgument,
                      register_name(frame.reg) + " frame is not motion feedback (register 0xFF)");
  }
  if (frame.body.size() < kFeedbackBodyBytes) {
    return make_error(ErrorCode::kInvalidArgument, "motion feedback frame carries " +
                                                       std::to_string(frame.body.size()) +
                                                       " bytes after its register, expected at least 14");
  }
  ByteReader reader(frame.body);
  reader.u8();  // status byte: the feedback is about another command
  MotionFeedback feedback;
  feedback.transaction_id = frame.transaction_id;
  feedback.type = reader.u8().value_or(0);
  feedback.command_reg = reader.u8().value_or(0);
  feedback.task_id = reader.u16_be().value_or(0);
  feedback.code = reader.u8().value_or(0);
  feedback.controller_time_us = reader.u64_be().value_or(0);
  return feedback;
}

Frame motion_feedback_frame(const MotionFeedback& feedback, std::uint16_t protocol) {
  ByteWriter body;
  body.u8(0)
      .u8(static_cast<std::uint8_t>(feedback.type))
      .u8(feedback.command_reg)
      .u16_be(feedback.task_id)
      .u8(static_cast<std::uint8_t>(feedback.code))
      .u64_be(feedback.controller_time_us);
  return Frame{
      .transaction_id = feedback.transaction_id, .protocol = protocol, .reg = kFeedbackRegister, .body = body.take()};
}

}  // namespace robotd::xarm
