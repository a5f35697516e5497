// What the command line sets (main.cpp), checked: one value per option.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "codec/parol6_frames.hpp"
#include "robotd/result.hpp"

namespace robotd::parol6::sim {

struct SimOptions {
  std::string pty_path;      // --pty: the symlink to the pseudo-terminal's device end
  std::string control_path;  // --control; empty: no control channel
  std::int64_t homing_ms = 3000;
  bool homed = false;                                              // start homed, at standby
  std::optional<std::array<std::int32_t, kJoints>> initial_steps;  // else 0 (or standby with homed)
  bool gripper = true;                                             // --no-gripper: nothing on the CAN bus
  bool quiet = false;
};

/// "a,b,c,d,e,f": six step counts within the 24-bit range the reply can carry.
Result<std::array<std::int32_t, kJoints>> parse_initial_steps(const std::string& text);

}  // namespace robotd::parol6::sim
