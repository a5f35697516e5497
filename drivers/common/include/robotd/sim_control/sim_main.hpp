// What every simulator's main() shares: its command line's exit status, its usage errors, its
// logger, how it is stopped, and the one "ready" line tests wait for.
#pragma once

#include <csignal>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace robotd::sim_control {

inline constexpr int kExitUsage = 2;

/// Parses the command line; nullopt to go on, else the status to exit with (0 after --help,
/// kExitUsage after a usage error, which CLI11 has printed).
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv);

/// "<program>: <message>" on stderr; returns kExitUsage.
int usage_error(const std::string& program, const std::string& message);

/// Adds `--rt-priority N` (SCHED_FIFO priority 1..99; 0, the default, keeps normal scheduling).
void add_rt_priority_option(CLI::App& app, int& priority);

/// Runs the calling thread, and the threads it starts later, SCHED_FIFO at `priority` (if not 0):
/// a simulator stands in for hardware, which has a CPU of its own, so ordinary load on the host
/// (compilers, sanitized tests) must not silence it for tens of milliseconds and fault robotd's
/// link. Tests and scripts/demo use a priority below robotd's loops. Where the system refuses
/// (no CAP_SYS_NICE, no RLIMIT_RTPRIO), logs a warning and goes on with normal scheduling.
void run_at_rt_priority(int priority);

/// spdlog to stderr under `program`; warnings and errors only when `quiet`.
void log_to_stderr(const std::string& program, bool quiet);

/// From now on SIGTERM and SIGINT set the returned flag (the simulator's loop ends when it is
/// set) and SIGPIPE is ignored: a client that vanished is no reason for a simulator to die.
const volatile std::sig_atomic_t& stop_on_signals();

/// "ready" on stdout, flushed: the one line stdout carries.
void announce_ready();

}  // namespace robotd::sim_control
