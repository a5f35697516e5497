// robotd-realman-sim: a RealMan arm controller (JSON over TCP, the UDP real-time push) on
// loopback, for tests and the no-hardware demo. README.md in this folder describes the options
// and the control channel.
//
//   robotd-realman-sim --port 18080 --control /tmp/realman.ctl
//
// Prints "ready" once it listens; runs until SIGTERM or SIGINT.
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
  std::cerr << "robotd-realman-sim: " << message << "\n";
  return kExitUsage;
}

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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int status = app.exit(error);
    return status == 0 ? 0 : kExitUsage;
  }
  options.generation = *robotd::realman::sim::parse_generation(generation);
  options.error_shape = *robotd::realman::sim::parse_error_shape(error_shape);
  const auto model = robotd::realman::find_model(options.model);
  if (!model) return fail("--model \"" + options.model + "\" is not a model it knows (" + known_models() + ")");

  auto logger = spdlog::stderr_logger_st("robotd-realman-sim");
  spdlog::set_default_logger(logger);
  spdlog::set_level(options.quiet ? spdlog::level::warn : spdlog::level::info);

  robotd::realman::sim::Simulator simulator(options, *model);
  if (auto opened = simulator.open(); !opened) return fail(opened.error().message);

  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  std::signal(SIGPIPE, SIG_IGN);

  spdlog::info("{} (generation {}, errors as {}) on {}:{}{}", options.model, generation, error_shape, options.host,
               options.port, options.control_path.empty() ? "" : ", control " + options.control_path);
  std::cout << "ready" << std::endl;  // the one line on stdout; flushed
  simulator.run(stop_requested);
  return 0;
}
