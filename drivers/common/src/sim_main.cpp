#include "robotd/sim_control/sim_main.hpp"

#include <iostream>

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

namespace robotd::sim_control {
namespace {

volatile std::sig_atomic_t stop_requested = 0;

void request_stop(int /*signal*/) { stop_requested = 1; }

}  // namespace

std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int status = app.exit(error);
    return status == 0 ? 0 : kExitUsage;
  }
  return std::nullopt;
}

int usage_error(const std::string& program, const std::string& message) {
  std::cerr << program << ": " << message << "\n";
  return kExitUsage;
}

void log_to_stderr(const std::string& program, bool quiet) {
  spdlog::set_default_logger(spdlog::stderr_logger_st(program));
  spdlog::set_level(quiet ? spdlog::level::warn : spdlog::level::info);
}

const volatile std::sig_atomic_t& stop_on_signals() {
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
  return stop_requested;
}

void announce_ready() { std::cout << "ready" << std::endl; }

}  // namespace robotd::sim_control
