// A robotd-imu-sim process for tests: a Yesense IMU streaming on a pty (its symlink at
// pty_path(), which an ImuSource or a test opens with transport::SerialPort) with a control
// channel, ready when it printed "ready"; steered or made to misbehave over that channel.
#pragma once

#include <string>
#include <vector>

#include "sim_process.hpp"

namespace robotd::testing {

class ImuSimProcess : public SimProcess {
 public:
  /// Starts the emulator with its pty symlink at `pty_path` (empty: a fresh path under /tmp)
  /// and `extra_args` (e.g. {"--rate-hz", "500", "--quiet"}); waits up to 5 s for it to be
  /// ready; throws std::runtime_error if it is not.
  explicit ImuSimProcess(std::string pty_path = {}, std::vector<std::string> extra_args = {});

  const std::string& pty_path() const { return link_path(); }

  /// The robotd-imu-sim executable under test.
  static std::string executable();
};

}  // namespace robotd::testing
