#include "device/black_box.hpp"

#include <thread>

namespace robotd::device {

BlackBox::BlackBox(DeviceChannel& channel, const control::DeviceModel& model) : channel_(channel), model_(model) {}

bool BlackBox::capture_if_frozen(const std::string& reason) {
  const std::lock_guard lock(mutex_);
  if (!channel_.black_box_frozen.load(std::memory_order_acquire)) return false;
  const std::uint64_t written = channel_.black_box_next.load(std::memory_order_acquire);
  const std::uint64_t count = std::min<std::uint64_t>(written, kBlackBoxTicks);
  records_.clear();
  records_.reserve(count);
  for (std::uint64_t i = written - count; i < written; ++i) records_.push_back(channel_.black_box[i % kBlackBoxTicks]);
  reason_ = reason;
  ++captures_;
  channel_.black_box_freeze_requested.store(false, std::memory_order_release);
  channel_.black_box_frozen.store(false, std::memory_order_release);
  return true;
}

Result<nlohmann::json> BlackBox::capture_now(std::chrono::milliseconds timeout) {
  std::uint64_t before = 0;
  {
    const std::lock_guard lock(mutex_);
    before = captures_;
  }
  channel_.black_box_freeze_requested.store(true, std::memory_order_release);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    capture_if_frozen("requested");
    {
      const std::lock_guard lock(mutex_);
      if (captures_ > before) break;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      channel_.black_box_freeze_requested.store(false, std::memory_order_release);
      return make_error(ErrorCode::kTimeout, "the loop of '" + model_.name + "' did not freeze its black box");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return latest();
}

nlohmann::json BlackBox::latest() const {
  const std::lock_guard lock(mutex_);
  if (captures_ == 0) return nullptr;
  nlohmann::json ticks = nlohmann::json::array();
  for (const auto& record : records_) {
    nlohmann::json q = nlohmann::json::array();
    nlohmann::json dq = nlohmann::json::array();
    nlohmann::json q_cmd = nlohmann::json::array();
    nlohmann::json tau_cmd = nlohmann::json::array();
    for (std::size_t j = 0; j < record.joint_count; ++j) {
      q.push_back(record.joints[j].position_rad);
      dq.push_back(record.joints[j].velocity_rad_s);
      q_cmd.push_back(record.joints[j].command_position_rad);
      tau_cmd.push_back(record.joints[j].command_torque_nm);
    }
    ticks.push_back({{"tick", record.tick},
                     {"time_ns", record.time_ns},
                     {"wake_latency_us", static_cast<double>(record.wake_latency_ns) / 1000.0},
                     {"execution_us", static_cast<double>(record.execution_ns) / 1000.0},
                     {"state", to_string(record.state)},
                     {"position_rad", q},
                     {"velocity_rad_s", dq},
                     {"command_position_rad", q_cmd},
                     {"command_torque_nm", tau_cmd}});
  }
  return {{"device", model_.name}, {"reason", reason_}, {"joint_names", model_.joint_names}, {"ticks", ticks}};
}

std::string BlackBox::summary() const {
  const std::lock_guard lock(mutex_);
  if (records_.empty()) return "black box of '" + model_.name + "' is empty";
  return "black box of '" + model_.name + "': ticks " + std::to_string(records_.front().tick) + ".." +
         std::to_string(records_.back().tick) + " kept (" + reason_ + "); read it with: robotctl call " + model_.name +
         " blackbox";
}

}  // namespace robotd::device
