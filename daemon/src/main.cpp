// robotd: the real-time robot middleware daemon. See README.md and docs/.
#include <csignal>
#include <iostream>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "app/daemon.hpp"
#include "app/systemd_notifier.hpp"
#include "config/config.hpp"

namespace {

constexpr int kExitConfigError = 2;
constexpr int kExitStartFailure = 1;

int wait_for_stop_signal() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  int received = 0;
  sigwait(&signals, &received);
  return received;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "robotd — real-time robot middleware: one DDS interface, exclusive control sessions, "
      "vendor drivers as plugins"};
  std::string config_path = ROBOTD_DEFAULT_CONFIG;
  bool check_only = false;
  std::string log_level;
  app.add_option("-c,--config", config_path, "config file (JSON, comments allowed)")->capture_default_str();
  app.add_flag("--check-config", check_only, "validate the config and exit (0 = valid)");
  app.add_option("--log-level", log_level, "override daemon.log_level")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  app.set_version_flag("--version", std::string("robotd ") + ROBOTD_VERSION);
  CLI11_PARSE(app, argc, argv);

  // Signals are taken by sigwait in main; every thread started from here on inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  auto config = robotd::config::load_config_file(config_path);
  if (!config) {
    std::cerr << "robotd: " << config.error().message << "\n";
    return kExitConfigError;
  }
  if (check_only) {
    std::cout << "robotd: config " << config_path << " is valid (" << config.value().devices.size() << " devices)\n";
    return 0;
  }
  spdlog::set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%^%l%$] %v");
  spdlog::set_level(spdlog::level::from_str(log_level.empty() ? config.value().daemon.log_level : log_level));
  spdlog::info("robotd {} starting with {}", ROBOTD_VERSION, config_path);

  robotd::app::Daemon daemon(std::move(config.value()));
  if (auto started = daemon.start(); !started) {
    spdlog::critical("robotd cannot start: {}", started.error().message);
    daemon.stop();
    return kExitStartFailure;
  }
  robotd::app::SystemdNotifier notifier;
  notifier.ready(daemon.summary());
  notifier.start_watchdog([&daemon] { return daemon.loop_problem(); });
  spdlog::info("robotd ready: {}", daemon.summary());

  const int signal = wait_for_stop_signal();
  spdlog::info("received {}, stopping", signal == SIGTERM ? "SIGTERM" : "SIGINT");
  notifier.stopping();
  notifier.stop_watchdog();
  daemon.stop();
  return 0;
}
