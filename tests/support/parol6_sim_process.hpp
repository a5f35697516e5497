// A robotd-parol6-sim process for tests: the board's firmware on a pty (its symlink at
// pty_path(), which a test or the driver opens with transport::SerialPort) with a control
// channel, ready when it printed "ready"; asked to report or misbehave over that channel.
#pragma once

#include <string>
#include <vector>

#include "sim_process.hpp"

namespace robotd::testing {

class Parol6SimProcess : public SimProcess {
 public:
  /// Starts the simulator with its pty symlink at `pty_path` (empty: a fresh path under /tmp)
  /// and `extra_args` (e.g. {"--homed", "--quiet"}); waits up to 5 s for it to be ready;
  /// throws std::runtime_error if it is not.
  explicit Parol6SimProcess(std::string pty_path = {}, std::vector<std::string> extra_args = {});

  const std::string& pty_path() const { return link_path(); }

  /// The robotd-parol6-sim executable under test.
  static std::string executable();
  /// A fresh path under /tmp, unique to this process and call: "/tmp/robotd-<stem>-<pid>-<n>"
  /// (no suffix: it is used for pty symlinks as well as sockets).
  static std::string unique_path(const std::string& stem) { return SimProcess::unique_path(stem, ""); }
};

}  // namespace robotd::testing
