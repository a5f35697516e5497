#include "joint_position_watch.hpp"

namespace robotctl {

JointPositionWatch::JointPositionWatch(robotd::Client& client, std::string device) : device_(std::move(device)) {
  subscription_ = client.on_joint_states([this](const robotd::JointState& state) {
    if (state.header.frame_id != device_) return;
    const std::lock_guard lock(mutex_);
    latest_ = state.position;
  });
}

std::optional<std::vector<double>> JointPositionWatch::latest() const {
  const std::lock_guard lock(mutex_);
  return latest_;
}

}  // namespace robotctl
