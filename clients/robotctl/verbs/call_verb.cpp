// call: a device operation (a driver op, or robotd's recover / blackbox) with JSON arguments.
#include <chrono>
#include <iostream>
#include <memory>

#include "exit_status.hpp"
#include "message_json.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {

Verb add_call_verb(CLI::App& app) {
  struct CallOptions {
    std::string device;
    std::string op;
    std::string args_json = "{}";
    int op_timeout_ms = 10'000;
  };
  auto options = std::make_shared<CallOptions>();
  CLI::App* command = app.add_subcommand(
      "call", "Run a device operation (a driver op, or robotd's recover and blackbox) and print its JSON result");
  command->add_option("DEVICE", options->device, "Device to call")->required();
  command->add_option("OP", options->op, "Operation name")->required();
  const CLI::Validator json_object(
      [](const std::string& text) {
        return Json::parse(text, nullptr, false).is_object()
                   ? std::string()
                   : "expected a JSON object such as '{\"fresh\": true}', got '" + text + "'";
      },
      "JSON object");
  command->add_option("JSON_ARGS", options->args_json, "Arguments")->check(json_object)->capture_default_str();
  command->add_option("--op-timeout-ms", options->op_timeout_ms, "Longest the operation may take, in ms")
      ->check(CLI::Range(1, 600'000))
      ->capture_default_str();
  command->footer(
      "Driver ops cover what joint commands do not: grippers, queries, configuration. 'robotctl devices --json' "
      "lists each device's ops and their arguments; one marked [needs free motors] acts on the joints, and robotd "
      "refuses it while a session holds a motor of the device. A refusal prints robotd's reason and exits 1.\n\n"
      "Example:\n  robotctl call arm state\n  robotctl call arm blackbox '{\"fresh\": true}'\n  robotctl call arm "
      "recover");
  return Verb{command, false, [options](VerbContext& context) {
                // Asking for the device list first fails fast (service timeout) when robotd is not there.
                if (auto devices = context.client.list_devices(); !devices) {
                  return report_failure(devices.error(), context.client.options());
                }
                auto result = context.client.device_call(options->device, options->op, options->args_json,
                                                         std::chrono::milliseconds(options->op_timeout_ms));
                if (!result) return report_failure(result.error(), context.client.options());
                const Json parsed = Json::parse(result.value(), nullptr, false);
                std::cout << (parsed.is_discarded() ? result.value() : pretty_text(parsed)) << std::endl;
                return kExitSuccess;
              }};
}

}  // namespace robotctl
