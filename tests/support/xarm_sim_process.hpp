// A robotd-xarm-sim process for tests: a UFACTORY xArm controller listening on a command port and
// a "real" report port of 127.0.0.1, with a control channel, ready when it printed "ready"; asked
// to report or misbehave over that channel. restart() brings it back on the same ports.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim_process.hpp"

namespace robotd::testing {

class XarmSimProcess : public SimProcess {
 public:
  /// Starts the simulator on `port` and `report_port` (0: a free port) with `extra_args` (e.g.
  /// {"--quiet", "--model", "xarm7"}) and waits up to 5 s for it to be ready; throws
  /// std::runtime_error if it is not.
  explicit XarmSimProcess(std::vector<std::string> extra_args = {}, std::uint16_t port = 0,
                          std::uint16_t report_port = 0);

  /// The command port on 127.0.0.1 (the controller's 502).
  std::uint16_t port() const;
  /// The 100 Hz "real" report port on 127.0.0.1 (the controller's 30003).
  std::uint16_t report_port() const { return report_port_; }

  /// The robotd-xarm-sim executable under test.
  static std::string executable();
  /// A TCP port on 127.0.0.1 that nothing listens on now (bound to port 0, read, closed).
  static std::uint16_t free_port();

 private:
  struct Ports {
    std::uint16_t command;
    std::uint16_t report;
  };
  /// `port` and `report_port`, a free port (not the other one) for each 0.
  static Ports choose(std::uint16_t port, std::uint16_t report_port);
  XarmSimProcess(std::vector<std::string> extra_args, Ports ports);

  std::uint16_t report_port_;
};

}  // namespace robotd::testing
