// What the command line sets (main.cpp), checked: one value per option, in SI units.
#pragma once

#include <array>
#include <string>

#include "codec/piper_frames.hpp"
#include "kinematics/piper_kinematics.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/can_transport.hpp"

namespace robotd::piper::sim {

struct SimOptions {
  transport::CanLinkConfig bus;  // --standin PATH or --interface NAME
  std::string control_path;      // --control; empty: no control channel
  std::string firmware = "S-V1.8-2";
  DhVariant dh = DhVariant::kOffset;
  double feedback_rate_hz = 200;  // the 0x2Ax / 0x25x group; 0x26x runs at a fifth of it
  std::array<double, kArmJoints> initial_rad{};
  bool leader = false;                  // --role leader: sends a leader's commands, no feedback
  std::uint8_t feedback_id_offset = 0;  // --feedback-id-offset: 0x2Ax sent at 0x2Ax + offset
  std::uint8_t control_id_offset = 0;   // --control-id-offset: 0x15x taken (a leader: sent) at 0x15x + offset
  bool quiet = false;
};

/// "q1,q2,q3,q4,q5,q6" in rad, each within the arm's default limits.
Result<std::array<double, kArmJoints>> parse_initial_joints(const std::string& text);

}  // namespace robotd::piper::sim
