// estop: engage the e-stop on one device or all (open to every client, no session needed), or
// reset it. It latches: only an explicit reset clears it.
#include <iostream>
#include <memory>

#include "exit_status.hpp"
#include "verbs/verbs.hpp"

namespace robotctl {

Verb add_estop_verb(CLI::App& app) {
  struct EstopOptions {
    std::string device;
    std::string reason;
    bool reset = false;
  };
  auto options = std::make_shared<EstopOptions>();
  CLI::App* command =
      app.add_subcommand("estop", "Engage the e-stop on a device or on every device, or reset it (--reset)");
  command->add_option("DEVICE", options->device, "Device to stop (default: every device)");
  auto* reason = command->add_option("--reason", options->reason, "Why, for robotd's log and robotctl status");
  command->add_flag("--reset", options->reset, "Reset the e-stop instead of engaging it")->excludes(reason);
  command->footer(
      "Any client may engage it; no session is needed. Each stopped device applies its safe behaviour and refuses "
      "commands and new sessions until the e-stop is reset: it latches.\n\n"
      "Example:\n  robotctl estop --reason \"cable snag\"     # every device\n  robotctl estop arm\n"
      "  robotctl estop --reset arm");
  return Verb{command, false, [options](VerbContext& context) {
                auto done = options->reset ? context.client.reset_estop(options->device)
                                           : context.client.estop(options->device, options->reason);
                if (!done) return report_failure(done.error(), context.client.options());
                std::cout << done.value().message << std::endl;
                return kExitSuccess;
              }};
}

}  // namespace robotctl
