// robotctl's verbs. Each add_*_verb registers a subcommand and its options on `app` and
// returns how to run it once the command line has been parsed and robotd's domain joined.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

#include "robotd/client/client.hpp"
#include "stop_signals.hpp"

namespace robotctl {

struct VerbContext {
  robotd::Client& client;
  StopSignals& stop;
};

struct Verb {
  CLI::App* command = nullptr;
  /// false: the verb has nothing to undo, so SIGINT and SIGTERM end the process as usual.
  bool handles_stop_signals = false;
  std::function<int(VerbContext&)> run;  // returns the exit status
};

Verb add_devices_verb(CLI::App& app);
Verb add_status_verb(CLI::App& app);
Verb add_sessions_verb(CLI::App& app);
Verb add_acquire_verb(CLI::App& app);
Verb add_release_verb(CLI::App& app);
Verb add_move_verb(CLI::App& app);
Verb add_estop_verb(CLI::App& app);
Verb add_echo_verb(CLI::App& app);
Verb add_record_verb(CLI::App& app);
Verb add_replay_verb(CLI::App& app);
Verb add_run_verb(CLI::App& app);
Verb add_call_verb(CLI::App& app);
Verb add_top_verb(CLI::App& app);

}  // namespace robotctl
