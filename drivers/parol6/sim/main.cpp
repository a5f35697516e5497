// robotd-parol6-sim: the PAROL6 control board's firmware on a pseudo-terminal, for tests and the
// no-hardware demo. README.md in this folder describes the options and the control channel.
//
//   robotd-parol6-sim --pty /tmp/parol6.tty --control /tmp/parol6.ctl
//
// Prints "ready" once the pty and the control socket are there; runs until SIGTERM or SIGINT.
#include <csignal>
#include <iostream>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "simulator.hpp"

namespace {

constexpr int kExitUsage = 2;

volatile std::sig_atomic_t stop_requested = 0;

void request_stop(int /*signal*/) { stop_requested = 1; }

int fail(const std::string& message) {
  std::cerr << "robotd-parol6-sim: " << message << "\n";
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  using robotd::parol6::sim::SimOptions;
  CLI::App app{"robotd-parol6-sim: the PAROL6 control board (six steppers, SSG-48 gripper) on a pseudo-terminal"};
  SimOptions options;
  std::string initial_steps;
  bool no_gripper = false;
  app.add_option("--pty", options.pty_path, "make a symlink at this path to the pseudo-terminal a driver opens")
      ->required();
  app.add_option("--control", options.control_path, "the control channel's unix stream socket path (tests)");
  app.add_option("--homing-ms", options.homing_ms, "how long command 100's homing sequence takes")
      ->check(CLI::Range(std::int64_t{100}, std::int64_t{600'000}))
      ->capture_default_str();
  app.add_flag("--homed", options.homed, "start homed, at the standby counters (10240,-32000,57905,0,0,32000)");
  app.add_option("--initial-steps", initial_steps, "the step counters at start: a,b,c,d,e,f (default all 0)");
  app.add_flag("--no-gripper", no_gripper, "no gripper on the board's CAN bus (the reply keeps its constants)");
  app.add_flag("--quiet", options.quiet, "log only warnings and errors to stderr");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int status = app.exit(error);
    return status == 0 ? 0 : kExitUsage;
  }
  if (options.pty_path.empty()) return fail("--pty needs a path");
  options.gripper = !no_gripper;
  if (!initial_steps.empty()) {
    auto steps = robotd::parol6::sim::parse_initial_steps(initial_steps);
    if (!steps) return fail(steps.error().message);
    options.initial_steps = steps.value();
  }

  auto logger = spdlog::stderr_logger_st("robotd-parol6-sim");
  spdlog::set_default_logger(logger);
  spdlog::set_level(options.quiet ? spdlog::level::warn : spdlog::level::info);

  robotd::parol6::sim::Simulator simulator(options);
  if (auto opened = simulator.open(); !opened) return fail(opened.error().message);

  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  std::signal(SIGPIPE, SIG_IGN);

  spdlog::info("pty {}, homing {} ms{}{}{}", options.pty_path, options.homing_ms, options.homed ? ", homed" : "",
               options.gripper ? ", SSG-48 gripper" : ", no gripper",
               options.control_path.empty() ? "" : ", control " + options.control_path);
  std::cout << "ready" << std::endl;  // the one line on stdout; flushed
  simulator.run(stop_requested);
  return 0;
}
