// connect()'s wait for the arm's own frames (a follower's feedback, a leader's joint commands)
// and, when they do not come, what arrived instead: nothing, the other role's frames, or the
// right frames at ids a MasterSlaveConfig offset moved.
#include <string>

#include "driver/hex_text.hpp"
#include "driver/piper_driver.hpp"
#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::piper {
namespace {

using namespace std::chrono_literals;

/// "… arrive at 0x2B1-0x2B8, moved by a feedback offset 0x10: set params.feedback_id_offset to 16 (0x10)".
std::string moved_ids_text(std::uint32_t first, std::uint32_t last, std::uint8_t offset, const char* kind,
                           const char* param) {
  return std::string("they arrive at ") + can_id_text(first + offset) + "-" + can_id_text(last + offset) +
         ", moved by a " + kind + " offset " + hex_text(offset, 2) + " (MasterSlaveConfig, 0x470): set params." +
         param + " to " + std::to_string(offset) + " (" + hex_text(offset, 2) + ")";
}

}  // namespace

bool PiperDriver::arm_frames_complete() const {
  return params_.leader() ? arm_.master_joints_seen : arm_.status_seen && arm_.joints_seen;
}

void PiperDriver::note_moved_ids(std::uint32_t wire_id) {
  if (const auto offset = feedback_offset_of(wire_id); offset && *offset != codec_.feedback_id_offset) {
    seen_feedback_offset_ = offset;
  }
  if (const auto offset = control_offset_of(wire_id); offset && *offset != codec_.control_id_offset) {
    seen_control_offset_ = offset;
  }
}

Result<void> PiperDriver::await_arm_frames(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  const std::uint64_t frames_before = rx_frames_;
  seen_feedback_offset_.reset();
  seen_control_offset_.reset();
  while (std::chrono::steady_clock::now() < deadline) {
    drain_link_blocking_free(driver::monotonic_now_ns());
    if (arm_frames_complete()) return {};
    if (!abort_.sleep_for(1ms)) {
      return driver::aborted_error(params_.leader() ? "waiting for the leader's commands"
                                                    : "waiting for the arm's feedback");
    }
  }
  return make_error(ErrorCode::kNotAvailable,
                    missing_frames_text(std::to_string(timeout.count()) + " ms", rx_frames_ != frames_before));
}

std::string PiperDriver::missing_frames_text(const std::string& waited, bool frames_arrived) const {
  const std::string link = transport_->describe();
  if (!frames_arrived) {
    return "no frames on " + link + " within " + waited +
           ": is the arm powered on, its CAN cable connected and the bus at 1 Mbit/s?";
  }
  if (params_.leader()) {
    const std::string head =
        "frames arrive on " + link + " but no leader joint commands (0x155-0x157) within " + waited + ": ";
    if (seen_control_offset_) {
      return head + moved_ids_text(can_id::kMotionControl, can_id::kMitControl + kArmJoints - 1, *seen_control_offset_,
                                   "control (the leader's linkage)", "control_id_offset");
    }
    if (arm_.status_seen || arm_.joints_seen) {
      return head +
             "the arm sends a follower's feedback (0x2A1, 0x2A5-0x2A7), so it is not set as leader: set it with "
             "MasterSlaveConfig 0xFA (op master_slave {\"role\": \"master\"} on a follower device) and restart it, "
             "or configure this device without \"role\": \"leader\"";
    }
    return head + "is the arm set as leader (MasterSlaveConfig 0xFA) and is it the one on this bus?";
  }
  const std::string head =
      "frames arrive on " + link + " but no arm feedback (status 0x2A1 and joints 0x2A5-0x2A7) within " + waited + ": ";
  if (seen_feedback_offset_) {
    return head + moved_ids_text(can_id::kArmStatus, can_id::kGripperFeedback, *seen_feedback_offset_, "feedback",
                                 "feedback_id_offset");
  }
  if (arm_.master_joints_seen) {
    return head +
           "the arm sends a leader's commands (0x151, 0x155-0x157, 0x159) and no feedback: it is set as leader "
           "(master, teach input). Read it with params.role \"leader\", or make it a follower with MasterSlaveConfig "
           "0xFC (op master_slave {\"role\": \"slave\"} on a leader device) and restart the arm";
  }
  return head +
         "an arm configured as master (teach input) sends none; make it a follower with the master_slave op "
         "{\"role\": \"slave\"} and restart it";
}

}  // namespace robotd::piper
