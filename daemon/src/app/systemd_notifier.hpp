// sd_notify: READY once every device is up, STOPPING on shutdown, and WATCHDOG pings from a
// thread that first checks that every RT loop is still ticking, so systemd restarts robotd
// when a loop hangs, not only when the process dies.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>

#include "robotd/driver/named_thread.hpp"

namespace robotd::app {

class SystemdNotifier {
 public:
  ~SystemdNotifier();

  void ready(const std::string& status);
  void stopping();
  /// If the unit has WatchdogSec=, pings at half that interval while `problem()` returns "".
  void start_watchdog(std::function<std::string()> problem);
  void stop_watchdog();

 private:
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  driver::NamedThread thread_;
};

}  // namespace robotd::app
