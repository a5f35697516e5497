// A real robotd process for end-to-end tests: started from a config text on its own DDS
// domain, its output captured to a log, stopped with SIGTERM (or killed) at the end.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd/client.hpp"

namespace robotd::testing {

/// A one-device config: a simulated arm named "arm" on `domain`, loopback DDS. `params`
/// replaces the sim params; `device_overrides` is merged into the device entry.
nlohmann::json sim_arm_config(int domain, const nlohmann::json& params = nullptr,
                              const nlohmann::json& device_overrides = nlohmann::json::object());

/// The test arm: 6 joints joint1..joint6, ±2.5 rad, default gains kp 300 / kd 10. With
/// `joint2_load_nm` != 0, joint2 carries that constant (gravity-like) torque, so letting go
/// or damping it is visible.
nlohmann::json sim_arm_params(double joint2_load_nm = 0);

ClientOptions client_options(int domain, const std::string& node_name = "test_client");

class RobotdProcess {
 public:
  /// Starts robotd with `config`. `environment` entries ("NAME=value") are added to its env.
  explicit RobotdProcess(const nlohmann::json& config, std::vector<std::string> environment = {});
  RobotdProcess(const RobotdProcess&) = delete;
  RobotdProcess& operator=(const RobotdProcess&) = delete;
  ~RobotdProcess();

  /// Waits until robotd answers list_devices and every device is RUNNING.
  bool wait_ready(Client& client, std::chrono::milliseconds timeout = std::chrono::seconds(15));
  /// SIGTERM, then waits; returns the exit status (or nullopt if it did not exit in time).
  std::optional<int> terminate(std::chrono::milliseconds timeout = std::chrono::seconds(10));
  /// Whether the process has exited; if so, its exit status.
  std::optional<int> exit_status();
  /// Waits for the process to exit on its own; its exit status, or nullopt after `timeout`.
  std::optional<int> wait_for_exit(std::chrono::milliseconds timeout = std::chrono::seconds(5));
  std::string log() const;
  pid_t pid() const { return pid_; }

 private:
  std::string config_path_;
  std::string log_path_;
  pid_t pid_ = -1;
  std::optional<int> status_;
};

/// Runs `program` with `arguments` as a child process; stdout is a pipe the test reads.
class ChildProcess {
 public:
  ChildProcess(const std::string& program, const std::vector<std::string>& arguments);
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();

  /// The next line the child printed, or nullopt after `timeout`.
  std::optional<std::string> read_line(std::chrono::milliseconds timeout);
  void kill_hard();  // SIGKILL and reap
  /// Sends `signal_number` (e.g. SIGINT, as Ctrl-C does).
  void send_signal(int signal_number) const;
  /// Waits up to `timeout` for the child to end and reaps it: its exit status (128 + the signal
  /// when a signal ended it), or nullopt while it still runs.
  std::optional<int> wait_exit(std::chrono::milliseconds timeout);
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  int stdout_fd_ = -1;
  std::string buffer_;
};

}  // namespace robotd::testing
