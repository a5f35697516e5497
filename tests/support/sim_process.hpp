// A simulator executable run as a child process for tests: started with its link (a stand-in
// bus socket or a pty symlink path, or a TCP port number) and a control channel, ready when it
// printed "ready"; asked to report or misbehave over that channel; killed and restarted on the
// same paths.
// PiperSimProcess, Parol6SimProcess and RealmanSimProcess are this with their simulator's options.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd_process.hpp"

namespace robotd::testing {

/// Every simulator a test starts runs SCHED_FIFO at this priority, below robotd's loops: it
/// stands in for hardware with a CPU of its own, which a loaded test machine must not starve.
inline constexpr int kSimRtPriority = 10;

class SimProcess {
 public:
  SimProcess(const SimProcess&) = delete;
  SimProcess& operator=(const SimProcess&) = delete;
  /// Kills it (hard) and removes the control path and the link path (if it is an absolute path).
  virtual ~SimProcess();

  /// One request, one reply over the control socket. Throws std::runtime_error when the
  /// socket cannot be reached or the reply is not JSON; an {"ok": false} reply is returned.
  nlohmann::json control(const nlohmann::json& request,
                         std::chrono::milliseconds timeout = std::chrono::milliseconds(2000)) const;

  /// SIGKILL: its link and control socket vanish without a goodbye (their files stay).
  void kill_hard();
  /// SIGTERM and wait; the exit status, or nullopt if it did not exit within `timeout`.
  std::optional<int> terminate(std::chrono::milliseconds timeout = std::chrono::seconds(5));
  /// Stops it (hard) if running and starts it again on the same paths, waiting for "ready".
  void restart();
  bool running() const { return child_ != nullptr; }

  const std::string& control_path() const { return control_path_; }

  /// A fresh path under /tmp, unique to this process and call: "/tmp/robotd-<stem>-<pid>-<n><suffix>".
  static std::string unique_path(const std::string& stem, const std::string& suffix = ".sock");

 protected:
  /// Starts `program` as `program <link_option> <link_path> --control <control path> <extra_args…>`
  /// (the control path fresh, from `stem`) and waits up to 5 s for "ready"; throws
  /// std::runtime_error if it does not come.
  SimProcess(std::string program, const std::string& stem, const std::string& link_option, std::string link_path,
             std::vector<std::string> extra_args);
  const std::string& link_path() const { return link_path_; }

 private:
  void start();

  std::string program_;
  std::string link_path_;
  std::string control_path_;
  std::vector<std::string> arguments_;
  std::unique_ptr<ChildProcess> child_;
};

/// Runs `program` with `arguments` to its end, stdout and stderr to /dev/null; its exit status
/// (128 + the signal when a signal ended it, −1 when it could not be started).
int run_to_exit(const std::string& program, const std::vector<std::string>& arguments);

}  // namespace robotd::testing
