// robotd-parol6-sim: the PAROL6 control board's firmware on a pseudo-terminal, for tests and the
// no-hardware demo. README.md in this folder describes the options and the control channel.
//
//   robotd-parol6-sim --pty /tmp/parol6.tty --control /tmp/parol6.ctl
//
// Prints "ready" once the pty and the control socket are there; runs until SIGTERM or SIGINT.
#include <csignal>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "robotd/sim_control/sim_main.hpp"
#include "simulator.hpp"

namespace {

constexpr const char* kProgram = "robotd-parol6-sim";

int fail(const std::string& message) { return robotd::sim_control::usage_error(kProgram, message); }

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
  int rt_priority = 0;
  robotd::sim_control::add_rt_priority_option(app, rt_priority);
  if (const auto exit_status = robotd::sim_control::parse_command_line(app, argc, argv)) return *exit_status;
  if (options.pty_path.empty()) return fail("--pty needs a path");
  options.gripper = !no_gripper;
  if (!initial_steps.empty()) {
    auto steps = robotd::parol6::sim::parse_initial_steps(initial_steps);
    if (!steps) return fail(steps.error().message);
    options.initial_steps = steps.value();
  }

  robotd::sim_control::log_to_stderr(kProgram, options.quiet);
  robotd::sim_control::run_at_rt_priority(rt_priority);

  robotd::parol6::sim::Simulator simulator(options);
  if (auto opened = simulator.open(); !opened) return fail(opened.error().message);

  const volatile std::sig_atomic_t& stop_requested = robotd::sim_control::stop_on_signals();

  spdlog::info("pty {}, homing {} ms{}{}{}", options.pty_path, options.homing_ms, options.homed ? ", homed" : "",
               options.gripper ? ", SSG-48 gripper" : ", no gripper",
               options.control_path.empty() ? "" : ", control " + options.control_path);
  robotd::sim_control::announce_ready();
  simulator.run(stop_requested);
  return 0;
}
