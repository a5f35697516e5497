// devices, status, sessions: what robotd serves and how it is doing.
#include <iostream>
#include <memory>

#include "exit_status.hpp"
#include "message_json.hpp"
#include "message_text.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {

Verb add_devices_verb(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand("devices", "List the devices robotd serves");
  command->add_flag("--json", *json, "Print robotd's device list as JSON (limits, ops, behaviour map included)");
  command->footer(
      "One row per device: name, driver and version, model, kinematic model (the arm model clients plan motion with), "
      "joints, loop rate, control modes, state.\n\n"
      "Example:\n  robotctl devices\n  robotctl --domain 7 devices --json");
  return Verb{command, false, [json](VerbContext& context) {
                auto devices = context.client.list_devices();
                if (!devices) return report_failure(devices.error(), context.client.options());
                std::cout << (*json ? pretty_text(to_json(devices.value())) + "\n" : device_table(devices.value()));
                return kExitSuccess;
              }};
}

Verb add_status_verb(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand(
      "status", "Show each device's health (state, e-stop, loop timing, command counters) and the sessions");
  command->add_flag("--json", *json, "Print {\"devices\": [DeviceStatus...], \"sessions\": SessionStatus} as JSON");
  command->footer(
      "Per device: state, fault, e-stop, control-loop timing (wake latency, execution time, period, overruns), "
      "commands received and accepted and every non-zero rejection by reason; then the active sessions (a closed-loop "
      "session's command success rate: the share of its last 100 ticks answered in time, its answers in time, late "
      "and never, and its minimum with what robotd does below it); then what "
      "robotd's DDS surface counted: commands that named no active session and no known device, each service's "
      "requests, refusals and oversized requests, and the DDS layer's warnings.\n\n"
      "Example:\n  robotctl status\n  robotctl status --json");
  return Verb{
      command, false, [json](VerbContext& context) {
        const robotd::ClientOptions& options = context.client.options();
        auto devices = context.client.list_devices();
        if (!devices) return report_failure(devices.error(), options);
        int status = kExitSuccess;
        Json device_statuses = Json::array();
        for (const auto& device : devices.value()) {
          auto device_status = context.client.next_device_status(device.name, options.service_timeout);
          if (!device_status) {
            status = report_failure(device_status.error(), options);
          } else if (*json) {
            device_statuses.push_back(to_json(device_status.value()));
          } else {
            std::cout << device_status_text(device_status.value()) << "\n";
          }
        }
        auto sessions = context.client.session_status(options.service_timeout);
        if (!sessions) return report_failure(sessions.error(), options);
        if (*json) {
          std::cout << pretty_text(Json{{"devices", device_statuses}, {"sessions", to_json(sessions.value())}}) << "\n";
        } else {
          std::cout << "sessions\n"
                    << session_table(sessions.value()) << "\n"
                    << surface_text(sessions.value().surface);
        }
        return status;
      }};
}

Verb add_sessions_verb(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand("sessions", "List the active control sessions");
  command->add_flag("--json", *json, "Print robotd's /session_status as JSON");
  command->footer(
      "One row per session: public session id (not the uuid, which only the session's holder knows), node, "
      "device, motors, mode, timeout fallback (requested → applied when the "
      "device cannot do what was asked), time left before it fires, commands accepted.\n\n"
      "Example:\n  robotctl sessions");
  return Verb{command, false, [json](VerbContext& context) {
                const robotd::ClientOptions& options = context.client.options();
                auto sessions = context.client.session_status(options.service_timeout);
                if (!sessions) return report_failure(sessions.error(), options);
                std::cout << (*json ? pretty_text(to_json(sessions.value())) + "\n" : session_table(sessions.value()));
                return kExitSuccess;
              }};
}

}  // namespace robotctl
