// The latest joint positions of one device, kept current by a /joint_states subscription.
#pragma once

#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "robotd/client/client.hpp"

namespace robotctl {

class JointPositionWatch {
 public:
  JointPositionWatch(robotd::Client& client, std::string device);
  JointPositionWatch(const JointPositionWatch&) = delete;
  JointPositionWatch& operator=(const JointPositionWatch&) = delete;
  ~JointPositionWatch() = default;

  /// Positions in rad, indexed by motor id; empty until the first sample.
  std::optional<std::vector<double>> latest() const;

 private:
  std::string device_;
  mutable std::mutex mutex_;
  std::optional<std::vector<double>> latest_;
  robotd::Subscription subscription_;  // last: its callbacks stop before the members they use go
};

}  // namespace robotctl
