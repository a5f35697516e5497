// What robotd last published about one device: its joint positions (/joint_states) and its state
// (/device_status), kept by the client's dispatch thread for the streaming thread to read.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "robotd/client.hpp"

namespace robotd::motion::detail {

struct DeviceCondition {
  DeviceState state = DeviceState::kConnecting;
  std::string text;  // state_text and fault_text, as robotd gave them
};

class DeviceWatch {
 public:
  DeviceWatch(Client& client, std::string device);
  DeviceWatch(const DeviceWatch&) = delete;
  DeviceWatch& operator=(const DeviceWatch&) = delete;

  /// Waits until a joint state and a device status of the device have come, at most `timeout`;
  /// an error (kTimeout) naming what is missing.
  Result<void> wait_for_first(std::chrono::milliseconds timeout);
  /// The newest positions, one per joint of the device (empty before the first joint state).
  std::vector<double> positions() const;
  DeviceCondition condition() const;

 private:
  std::string device_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<double> positions_;
  std::optional<DeviceCondition> condition_;
  // Last: they go first, so that no callback runs on a half-destroyed watch.
  Subscription joint_states_;
  Subscription device_statuses_;
};

}  // namespace robotd::motion::detail
