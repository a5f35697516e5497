// The second layer of the safety scenarios: the same scenario run through the services around
// the loop, as robotd wires them — a Device whose loop the rig ticks at simulated times, the
// SessionService (request_control, release_control), the CommandGate every /control_command
// passes, and DeviceServices (/estop, recover, reset_zero) with their maintenance running on
// threads of their own, as robotd's service workers do. Every tick goes through the same
// InvariantChecker, plus what only the services can break: a session granted while
// maintenance holds the device, a recover under live sessions, a command accepted while the
// e-stop is engaged.
//
// The rig keeps a run deterministic: before each tick it waits for a service thread to reach
// the point the loop can see (the e-stop flag set, maintenance requested, maintenance handed
// back), so a seed replays exactly.
#pragma once

#include <cstdio>

#include "loop_rig.hpp"
#include "scenario.hpp"

namespace robotd::safety {

RunResult run_scenario_through_services(const Scenario& scenario, std::FILE* trace = nullptr);

}  // namespace robotd::safety
