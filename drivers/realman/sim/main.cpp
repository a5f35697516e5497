// robotd-realman-sim: a RealMan arm controller (JSON over TCP, the UDP real-time push) on
// loopback, for tests and the no-hardware demo. README.md in this folder describes the options
// and the control channel.
//
//   robotd-realman-sim --port 18080 --control /tmp/realman.ctl
//
// Prints "ready" once it listens; runs until SIGTERM or SIGINT.
#include <csignal>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "robotd/sim_control/sim_main.hpp"
#include "simulator.hpp"

namespace {

constexpr const char* kProgram = "robotd-realman-sim";

int fail(const std::string& message) { return robotd::sim_control::usage_error(kProgram, message); }

std::string known_models() {
  std::string names;
  for (const auto& model : robotd::realman::known_models()) {
    names += (names.empty() ? "" : ", ") + std::string(model.name) + "-B";
  }
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  using robotd::realman::sim::SimOptions;
  CLI::App app{"robotd-realman-sim: a RealMan arm controller (JSON over TCP, UDP real-time push) on loopback"};
  SimOptions options;
  std::string generation = "3";
  std::string error_shape = "list";
  app.add_option("--port", options.port, "the TCP command port (the real controller's is 8080)")
      ->required()
      ->check(CLI::Range(1, 65535));
  app.add_option("--host", options.host, "the IPv4 address to listen on")->capture_default_str();
  app.add_option("--control", options.control_path, "the control channel's unix stream socket path (tests)");
  app.add_option("--model", options.model, "the Product_version reported (RM65-B, RM65-6F, RM75-B, GEN72-B …)")
      ->capture_default_str();
  app.add_option("--generation", generation, "controller generation: 2, 3 or 4")
      ->check(CLI::IsMember({"2", "3", "4"}))
      ->capture_default_str();
  app.add_option("--error-shape", error_shape,
                 "errors as \"err\":[…] (list), \"arm_err\"/\"sys_err\" (legacy), \"err\":n (scalar)")
      ->check(CLI::IsMember({"list", "legacy", "scalar"}))
      ->capture_default_str();
  app.add_flag("--quiet", options.quiet, "log only warnings and errors to stderr");
  int rt_priority = 0;
  robotd::sim_control::add_rt_priority_option(app, rt_priority);
  if (const auto exit_status = robotd::sim_control::parse_command_line(app, argc, argv)) return *exit_status;
  options.generation = *robotd::realman::sim::parse_generation(generation);
  options.error_shape = *robotd::realman::sim::parse_error_shape(error_shape);
  const auto model = robotd::realman::find_model(options.model);
  if (!model) return fail("--model \"" + options.model + "\" is not a model it knows (" + known_models() + ")");

  robotd::sim_control::log_to_stderr(kProgram, options.quiet);
  robotd::sim_control::run_at_rt_priority(rt_priority);

  robotd::realman::sim::Simulator simulator(options, *model);
  if (auto opened = simulator.open(); !opened) return fail(opened.error().message);

  const volatile std::sig_atomic_t& stop_requested = robotd::sim_control::stop_on_signals();

  spdlog::info("{} (generation {}, errors as {}) on {}:{}{}", options.model, generation, error_shape, options.host,
               options.port, options.control_path.empty() ? "" : ", control " + options.control_path);
  robotd::sim_control::announce_ready();
  simulator.run(stop_requested);
  return 0;
}
