// robotd-xarm-sim: a UFACTORY xArm controller (xArm 5/6/7, Lite 6, 850) on loopback, over its
// private TCP protocol — the command port and the report ports — for tests and the no-hardware
// demo. README.md in this folder describes the options and the control channel.
//
//   robotd-xarm-sim --port 15020 --report-port 15023 --model xarm6 --control /tmp/xarm.ctl
//
// Prints "ready" once every port listens; runs until SIGTERM or SIGINT.
#include <csignal>
#include <cstdint>
#include <optional>
#include <regex>
#include <string>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "robotd/sim_control/sim_main.hpp"
#include "simulator.hpp"

namespace {

constexpr const char* kProgram = "robotd-xarm-sim";

int fail(const std::string& message) { return robotd::sim_control::usage_error(kProgram, message); }

std::string known_models() {
  std::string names;
  for (const auto& model : robotd::xarm::known_models()) names += (names.empty() ? "" : ", ") + std::string(model.name);
  return names;
}

/// The report port an option set, if it did.
std::optional<std::uint16_t> report_port(int port) {
  if (port == 0) return std::nullopt;
  return static_cast<std::uint16_t>(port);
}

}  // namespace

int main(int argc, char** argv) {
  using robotd::xarm::sim::SimOptions;
  CLI::App app{"robotd-xarm-sim: a UFACTORY xArm controller (private TCP protocol, report ports) on loopback"};
  SimOptions options;
  int real_port = 0;
  int normal_port = 0;
  int realtime_port = 0;
  int rich_port = 0;
  app.add_option("--port", options.port, "the command port (the real controller's is 502)")
      ->required()
      ->check(CLI::Range(1, 65535));
  app.add_option("--report-port", real_port, "serve the 100 Hz \"real\" report here (the controller's 30003)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--normal-report-port", normal_port, "serve the 5 Hz \"normal\" report here (30001)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--realtime-report-port", realtime_port, "serve the 250 Hz real-time report here (30000)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--rich-report-port", rich_port, "serve the 5 Hz \"rich\" report here (30002, the SDK's default)")
      ->check(CLI::Range(1, 65535));
  app.add_flag("--report-ft", options.report_force_torque, "real reports with the F/T fields (135 bytes, not 87)");
  app.add_option("--host", options.host, "the IPv4 address to listen on")->capture_default_str();
  app.add_option("--model", options.model, "the arm (xarm5, xarm6, xarm7, lite6, uf850 …)")->capture_default_str();
  app.add_option("--firmware", options.firmware, "the firmware version get_version reports (MAJ.MIN.REV)")
      ->capture_default_str();
  app.add_option("--control", options.control_path, "the control channel's unix stream socket path (tests)");
  app.add_flag("--quiet", options.quiet, "log only warnings and errors to stderr");
  int rt_priority = 0;
  robotd::sim_control::add_rt_priority_option(app, rt_priority);
  if (const auto exit_status = robotd::sim_control::parse_command_line(app, argc, argv)) return *exit_status;
  options.report_port = report_port(real_port);
  options.normal_report_port = report_port(normal_port);
  options.realtime_report_port = report_port(realtime_port);
  options.rich_report_port = report_port(rich_port);
  const auto model = robotd::xarm::find_model(options.model);
  if (!model) return fail("--model \"" + options.model + "\" is not a model it knows (" + known_models() + ")");
  if (!std::regex_match(options.firmware, std::regex(R"(\d{1,3}\.\d{1,3}\.\d{1,3})"))) {
    return fail("--firmware \"" + options.firmware + "\" is not MAJ.MIN.REV (e.g. 2.3.0)");
  }

  robotd::sim_control::log_to_stderr(kProgram, options.quiet);
  robotd::sim_control::run_at_rt_priority(rt_priority);

  robotd::xarm::sim::Simulator simulator(options, *model);
  if (auto opened = simulator.open(); !opened) return fail(opened.error().message);

  const volatile std::sig_atomic_t& stop_requested = robotd::sim_control::stop_on_signals();

  spdlog::info("{} (firmware {}) on {}:{}{}", model->display, options.firmware, options.host, options.port,
               options.control_path.empty() ? "" : ", control " + options.control_path);
  robotd::sim_control::announce_ready();
  simulator.run(stop_requested);
  return 0;
}
