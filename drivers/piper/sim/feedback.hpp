// The frames the arm streams on its own (spec §2.1): the 200 Hz group (0x2A1 status, 0x2A2–0x2A4
// end pose, 0x2A5–0x2A7 joints, 0x2A8 gripper, 0x251–0x256 driver high-speed info) and the
// 40 Hz group (0x261–0x266 driver low-speed info), read from the arm model.
#pragma once

#include <vector>

#include "arm_model.hpp"
#include "codec/piper_frames.hpp"

namespace robotd::piper::sim {

void append_high_rate_feedback(const ArmModel& arm, const CodecOptions& options, std::vector<CanMessage>& out);
void append_low_rate_feedback(const ArmModel& arm, const CodecOptions& options, std::vector<CanMessage>& out);
/// A leader (master) arm's stream instead of feedback (piper_sdk asserts/double_piper.MD): 0x151
/// (CAN command, MOVE J, 0xAD high-follow, which sets its follower so), 0x155–0x157 with its
/// joints, 0x159 with its gripper.
void append_leader_commands(const ArmModel& arm, const CodecOptions& options, std::vector<CanMessage>& out);

}  // namespace robotd::piper::sim
