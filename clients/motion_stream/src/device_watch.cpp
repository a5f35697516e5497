#include "device_watch.hpp"

namespace robotd::motion::detail {

DeviceWatch::DeviceWatch(Client& client, std::string device) : device_(std::move(device)) {
  joint_states_ = client.on_joint_states([this](const JointState& state) {
    if (state.header.frame_id != device_) return;
    {
      const std::lock_guard lock(mutex_);
      positions_ = state.position;
    }
    changed_.notify_all();
  });
  device_statuses_ = client.on_device_status([this](const DeviceStatus& status) {
    if (status.device != device_) return;
    {
      const std::lock_guard lock(mutex_);
      std::string text = status.state_text;
      if (!status.fault_text.empty()) text += (text.empty() ? "" : "; ") + status.fault_text;
      condition_ = DeviceCondition{status.state, std::move(text)};
    }
    changed_.notify_all();
  });
}

Result<void> DeviceWatch::wait_for_first(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  if (changed_.wait_for(lock, timeout, [this] { return !positions_.empty() && condition_.has_value(); })) return {};
  const std::string missing =
      positions_.empty() ? (condition_ ? "/joint_states" : "/joint_states nor /device_status") : "/device_status";
  return make_error(ErrorCode::kTimeout, "no " + missing + " of '" + device_ + "' within " +
                                             std::to_string(timeout.count()) + " ms (is robotd running the device?)");
}

std::vector<double> DeviceWatch::positions() const {
  const std::lock_guard lock(mutex_);
  return positions_;
}

DeviceCondition DeviceWatch::condition() const {
  const std::lock_guard lock(mutex_);
  return condition_.value_or(DeviceCondition{});
}

}  // namespace robotd::motion::detail
