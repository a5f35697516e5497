// A robotd-piper-sim process for tests: started on a stand-in CAN bus path with a control
// channel, ready when it printed "ready"; asked to report or misbehave over that channel.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sim_process.hpp"

namespace robotd::testing {

/// Joints of a PiPER device as robotd describes it: the six arm joints and the gripper.
inline constexpr std::size_t kPiperDeviceJoints = 7;

class PiperSimProcess : public SimProcess {
 public:
  /// Starts the simulator on `bus_path` (empty: a fresh path under /tmp) with `extra_args`
  /// (e.g. {"--initial", "0,0.5,-0.5,0,0,0"}) and waits up to 5 s for it to be ready; throws
  /// std::runtime_error if it is not.
  explicit PiperSimProcess(std::string bus_path = {}, std::vector<std::string> extra_args = {});

  const std::string& bus_path() const { return link_path(); }

  /// The robotd-piper-sim executable under test.
  static std::string executable();
};

}  // namespace robotd::testing
