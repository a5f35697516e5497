// A robotd-piper-sim process for tests: started on a stand-in CAN bus path with a control
// channel, ready when it printed "ready"; asked to report or misbehave over that channel.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd_process.hpp"

namespace robotd::testing {

class PiperSimProcess {
 public:
  /// Starts the simulator on `bus_path` (empty: a fresh path under /tmp) with `extra_args`
  /// (e.g. {"--initial", "0,0.5,-0.5,0,0,0"}) and waits up to 5 s for it to be ready; throws
  /// std::runtime_error if it is not.
  explicit PiperSimProcess(std::string bus_path = {}, std::vector<std::string> extra_args = {});
  PiperSimProcess(const PiperSimProcess&) = delete;
  PiperSimProcess& operator=(const PiperSimProcess&) = delete;
  ~PiperSimProcess();

  /// One request, one reply over the control socket. Throws std::runtime_error when the
  /// socket cannot be reached or the reply is not JSON; an {"ok": false} reply is returned.
  nlohmann::json control(const nlohmann::json& request,
                         std::chrono::milliseconds timeout = std::chrono::milliseconds(2000)) const;

  /// SIGKILL: the bus and control sockets vanish without a goodbye (their files stay).
  void kill_hard();
  /// SIGTERM and wait; the exit status, or nullopt if it did not exit within `timeout`.
  std::optional<int> terminate(std::chrono::milliseconds timeout = std::chrono::seconds(5));
  /// Stops it (hard) if running and starts it again on the same paths, waiting for "ready".
  void restart();
  bool running() const { return child_ != nullptr; }

  const std::string& bus_path() const { return bus_path_; }
  const std::string& control_path() const { return control_path_; }

  /// The robotd-piper-sim executable under test.
  static std::string executable();
  /// A fresh socket path under /tmp, unique to this process and call: "/tmp/robotd-<stem>-<pid>-<n>.sock".
  static std::string unique_path(const std::string& stem);

 private:
  void start();

  std::string bus_path_;
  std::string control_path_;
  std::vector<std::string> extra_args_;
  std::unique_ptr<ChildProcess> child_;
};

}  // namespace robotd::testing
