// robotd-imu-sim: a Yesense IMU streaming its serial output protocol on a pseudo-terminal, for
// tests and the no-hardware demo. README.md in this folder describes the options, the motion and
// the control channel.
//
//   robotd-imu-sim --pty /tmp/imu.tty --control /tmp/imu.ctl --rate-hz 200
//
// Prints "ready" once the pty and the control socket are there; runs until SIGTERM or SIGINT.
#include <csignal>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "imu_simulator.hpp"
#include "robotd/sim_control/sim_main.hpp"

namespace {

constexpr const char* kProgram = "robotd-imu-sim";

}  // namespace

int main(int argc, char** argv) {
  using robotd::imu::sim::SimOptions;
  CLI::App app{"robotd-imu-sim: a Yesense IMU (YIS series) streaming its serial output protocol on a pseudo-terminal"};
  SimOptions options;
  app.add_option("--pty", options.pty_path, "make a symlink at this path to the pseudo-terminal a driver opens")
      ->required();
  app.add_option("--control", options.control_path, "the control channel's unix stream socket path (tests)");
  app.add_option("--rate-hz", options.rate_hz, "output frames per second")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_flag("--quiet", options.quiet, "log only warnings and errors to stderr");
  int rt_priority = 0;
  robotd::sim_control::add_rt_priority_option(app, rt_priority);
  if (const auto exit_status = robotd::sim_control::parse_command_line(app, argc, argv)) return *exit_status;
  if (options.pty_path.empty()) return robotd::sim_control::usage_error(kProgram, "--pty needs a path");

  robotd::sim_control::log_to_stderr(kProgram, options.quiet);
  robotd::sim_control::run_at_rt_priority(rt_priority);

  robotd::imu::sim::ImuSimulator simulator(options);
  if (auto opened = simulator.open(); !opened)
    return robotd::sim_control::usage_error(kProgram, opened.error().message);

  const volatile std::sig_atomic_t& stop_requested = robotd::sim_control::stop_on_signals();

  spdlog::info("pty {}, {} Hz{}", options.pty_path, options.rate_hz,
               options.control_path.empty() ? "" : ", control " + options.control_path);
  robotd::sim_control::announce_ready();
  simulator.run(stop_requested);
  return 0;
}
