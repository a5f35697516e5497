// A robotd-realman-sim process for tests: a RealMan controller listening on a TCP port of
// 127.0.0.1 (its UDP push goes where set_realtime_push says) with a control channel, ready when
// it printed "ready"; asked to report or misbehave over that channel. restart() brings it back on
// the same port.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim_process.hpp"

namespace robotd::testing {

class RealmanSimProcess : public SimProcess {
 public:
  /// Starts the simulator on `port` (0: a free port) with `extra_args` (e.g. {"--quiet",
  /// "--model", "RM75-B"}) and waits up to 5 s for it to be ready; throws std::runtime_error if
  /// it is not.
  explicit RealmanSimProcess(std::vector<std::string> extra_args = {}, std::uint16_t port = 0);

  /// The TCP command port on 127.0.0.1.
  std::uint16_t port() const;

  /// The robotd-realman-sim executable under test.
  static std::string executable();
  /// A TCP port on 127.0.0.1 that nothing listens on now (bound to port 0, read, closed).
  static std::uint16_t free_port();
};

}  // namespace robotd::testing
