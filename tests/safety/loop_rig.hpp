// Runs a scenario against the real ControlLoop, tick by tick at simulated times, playing the
// service side the way robotd does: the session table grants and ends sessions and posts their
// events, commands pass the real validator into the real command mailbox, the e-stop and
// maintenance flags are set on the device channel, and a maintenance "thread" runs recover or
// reset_zero for as long as the scenario says unless the loop aborts it. Every tick goes
// through the InvariantChecker; the first violation ends the run.
#pragma once

#include <array>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "client_commands.hpp"
#include "device/command_mailbox.hpp"
#include "device/control_loop.hpp"
#include "invariant_checker.hpp"
#include "plant_driver.hpp"
#include "scenario.hpp"
#include "session/session_table.hpp"

namespace robotd::safety {

struct RunResult {
  std::optional<Violation> violation;
  std::size_t events_run = 0;  // events before (and including) the failing one
  std::uint64_t ticks = 0;
  std::uint64_t commands_accepted = 0;
  std::uint64_t commands_rejected = 0;
  std::uint64_t commands_unknown_session = 0;  // of the rejected: no live session has the uuid
  std::uint64_t sessions_granted = 0;
  std::uint64_t sessions_ended_for_rate = 0;      // closed-loop sessions whose rate fell below a FALLBACK minimum
  std::uint64_t rate_warnings = 0;                // ... below a WARN minimum
  std::array<std::uint64_t, 7> ticks_in_state{};  // by DeviceState: how much of the run each state took
};

/// Runs `scenario`. With `trace`, writes one line per tick: the state, the events posted, and
/// each joint's reading and command (for a person reading a shrunk failure).
RunResult run_scenario(const Scenario& scenario, std::FILE* trace = nullptr);

/// A way to run a scenario: run_scenario, or run_scenario_through_services (service_rig).
using Runner = RunResult (*)(const Scenario& scenario, std::FILE* trace);

}  // namespace robotd::safety
