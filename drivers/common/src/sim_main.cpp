#include "robotd/sim_control/sim_main.hpp"

#include <cerrno>
#include <iostream>
#include <sched.h>

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "errno_text.hpp"

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

void add_rt_priority_option(CLI::App& app, int& priority) {
  app.add_option("--rt-priority", priority,
                 "run SCHED_FIFO at this priority (1-99), like hardware with a CPU of its own; 0: normal scheduling")
      ->check(CLI::Range(0, 99))
      ->capture_default_str();
}

void run_at_rt_priority(int priority) {
  if (priority == 0) return;
  const sched_param param{.sched_priority = priority};
  if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
    spdlog::warn("cannot run SCHED_FIFO at priority {} ({}): normal scheduling, so load on this host can delay replies",
                 priority, transport::errno_text(errno));
  }
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
