// The ControlCommands a scenario's clients send. A command event carries only a seed; what it
// becomes is drawn from that seed, the session it claims and the time it is sent: mostly
// points of a smooth trajectory (each client its own), otherwise far jumps, values beyond the
// limits, NaN and Inf, arrays of the wrong length, motors the session does not hold, another
// device's name. Deterministic, so a shrunk scenario replays the same commands.
#pragma once

#include <cstdint>
#include <string>

#include "robotd/messages.hpp"
#include "scenario.hpp"

namespace robotd::safety {

struct ClientSession {
  int label = 0;
  std::string uuid;
  ControlMode mode = ControlMode::kPosition;
  std::uint64_t motors = 0;
};

ControlCommand client_command(const ClientSession& session, std::uint32_t seed, const DeviceSpec& device,
                              std::int64_t now_ns);

/// The tick a command event answers (ControlCommand.answers_tick), `newest` being the newest
/// tick whose state the client has seen; 0 = none.
std::uint64_t answered_tick(const Event& command, std::uint64_t newest);

}  // namespace robotd::safety
