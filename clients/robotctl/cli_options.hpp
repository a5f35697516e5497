// Command-line options shared by robotctl's verbs: where robotd is (global), and the session
// settings several verbs take (motors, control mode, timeout and release behaviour).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "robotd/client/options.hpp"
#include "robotd/messages.hpp"

namespace robotctl {

/// --domain, --interface, --peers, --multicast, --timeout-ms and --node-name, written into
/// `options`; its current values (from the environment) are the defaults.
void add_connection_options(CLI::App& app, robotd::ClientOptions& options);

/// --motors 0,1,2: motor ids of the device; none given means every motor.
CLI::Option* add_motors_option(CLI::App& command, std::vector<std::int32_t>& motor_ids);
/// --mode position|torque|mixed.
CLI::Option* add_control_mode_option(CLI::App& command, robotd::ControlMode& mode);
/// `name` keep|damping|zero_torque (--on-timeout, --on-release, --mode of release).
CLI::Option* add_behavior_option(CLI::App& command, const std::string& name, robotd::Behavior& behavior,
                                 const std::string& description);

}  // namespace robotctl
