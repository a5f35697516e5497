// What the services need to know about a running device that only its state publisher (the
// single reader of the loop's outputs) can tell: the newest loop state and the loop timing.
#pragma once

#include <nlohmann/json.hpp>

#include "device/device_channel.hpp"

namespace robotd::service {

class DeviceObserver {
 public:
  virtual ~DeviceObserver() = default;

  /// The newest state the loop published (tick 0 = none yet).
  virtual device::LoopState latest() const = 0;
  /// Loop timing over the statistics window: percentiles of wake latency, execution time and
  /// period, ticks, overruns, /joint_states published (with the stamp of the last one counted);
  /// with `samples`, every sample (ns).
  /// `reset` empties the window afterwards, so the next call covers only what follows.
  virtual nlohmann::json loop_timing(bool samples, bool reset) = 0;
};

}  // namespace robotd::service
