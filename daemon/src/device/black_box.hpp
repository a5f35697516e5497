// The non-RT half of the black box: when the loop freezes its ring of recent ticks (on a
// fault, or when asked), copy it out, keep it for `robotctl call <device> blackbox`, and let
// the loop resume writing.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "control/device_model.hpp"
#include "device/device_channel.hpp"
#include "robotd/result.hpp"

namespace robotd::device {

class BlackBox {
 public:
  BlackBox(DeviceChannel& channel, const control::DeviceModel& model);

  /// If the loop has frozen the ring, copies it (oldest tick first) and unfreezes it.
  /// Returns true if it captured.
  bool capture_if_frozen(const std::string& reason);
  /// Asks the loop to freeze now and returns the capture (for an on-demand dump).
  Result<nlohmann::json> capture_now(std::chrono::milliseconds timeout);
  /// The last capture as JSON, or null if there is none.
  nlohmann::json latest() const;
  /// One line for the log: what was captured and how to get it.
  std::string summary() const;

 private:
  DeviceChannel& channel_;
  const control::DeviceModel& model_;
  mutable std::mutex mutex_;
  std::vector<BlackBoxRecord> records_;
  std::string reason_;
  std::uint64_t captures_ = 0;
};

}  // namespace robotd::device
