#include "app/systemd_notifier.hpp"

#include <chrono>

#include <spdlog/spdlog.h>
#include <systemd/sd-daemon.h>

namespace robotd::app {

SystemdNotifier::~SystemdNotifier() { stop_watchdog(); }

void SystemdNotifier::ready(const std::string& status) { sd_notifyf(0, "READY=1\nSTATUS=%s", status.c_str()); }

void SystemdNotifier::stopping() { sd_notify(0, "STOPPING=1\nSTATUS=stopping: bringing devices to a safe stop"); }

void SystemdNotifier::start_watchdog(std::function<std::string()> problem) {
  std::uint64_t interval_us = 0;
  if (sd_watchdog_enabled(0, &interval_us) <= 0) return;
  const auto period = std::chrono::microseconds(interval_us / 2);
  spdlog::info("systemd watchdog: pinging every {} ms while every loop ticks", period.count() / 1000);
  thread_ = driver::NamedThread("watchdog", [this, period, problem = std::move(problem)] {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, period, [this] { return stopping_; })) {
      const std::string trouble = problem();
      if (trouble.empty()) {
        sd_notify(0, "WATCHDOG=1");
      } else {
        spdlog::error("not pinging the systemd watchdog: {}", trouble);
      }
    }
  });
}

void SystemdNotifier::stop_watchdog() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

}  // namespace robotd::app
