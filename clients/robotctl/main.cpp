// robotctl: inspect and drive the robots a robotd serves, from a shell.
//
//   robotctl devices
//   robotctl move arm --to 0.5,0,0,0,0,0
#include <algorithm>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_options.hpp"
#include "exit_status.hpp"
#include "robotd/client/client.hpp"
#include "stop_signals.hpp"
#include "verbs/verbs.hpp"

int main(int argc, char** argv) {
  using namespace robotctl;

  // Before anything starts a thread, so that only the signalfd sees SIGINT and SIGTERM.
  auto stop = StopSignals::install();
  if (!stop) return report_failure(stop.error().message);

  robotd::ClientOptions options = robotd::ClientOptions::from_environment();
  options.node_name = "robotctl";

  CLI::App app{"robotctl: inspect and drive the robots robotd serves, over DDS."};
  app.fallthrough();  // global options may also follow the verb
  app.require_subcommand(1);
  app.footer("Run 'robotctl VERB --help' for a verb's options and an example.");
  add_connection_options(app, options);
  const std::vector<Verb> verbs = {
      add_devices_verb(app), add_status_verb(app), add_sessions_verb(app), add_acquire_verb(app), add_release_verb(app),
      add_move_verb(app),    add_estop_verb(app),  add_echo_verb(app),     add_record_verb(app),  add_replay_verb(app),
      add_run_verb(app),     add_call_verb(app),   add_top_verb(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int status = app.exit(error);
    return status == kExitSuccess ? kExitSuccess : kExitUsage;
  }

  const auto verb = std::find_if(verbs.begin(), verbs.end(), [](const Verb& v) { return v.command->parsed(); });
  auto client = robotd::Client::connect(options);
  if (!client) return report_failure(client.error(), options);
  if (!verb->handles_stop_signals) stop.value().restore_default_action();
  VerbContext context{client.value(), stop.value()};
  return verb->run(context);
}
