#include "device/command_admission.hpp"

namespace robotd::device {

std::optional<CommandRefusal> command_refusal(const DeviceChannel& channel) {
  const DeviceState state = channel.device_state.load(std::memory_order_acquire);
  if (state == DeviceState::kEstop || channel.estop.load(std::memory_order_acquire)) {
    return CommandRefusal{control::Rejection::kEstop, "device is e-stopped; reset the e-stop first"};
  }
  if (state != DeviceState::kRunning) {
    return CommandRefusal{control::Rejection::kFault, "device is " + std::string(to_string(state)) + ", not RUNNING"};
  }
  return std::nullopt;
}

}  // namespace robotd::device
