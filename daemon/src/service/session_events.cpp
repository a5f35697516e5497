#include "service/session_events.hpp"

#include "rt/monotonic_clock.hpp"

namespace robotd::service {

device::ControlEvent session_start_event(const session::SessionRecord& record) {
  device::ControlEvent event;
  event.type = device::ControlEvent::Type::kSessionStart;
  event.slot = record.slot;
  event.generation = record.generation;
  event.mode = record.mode;
  event.behavior = record.applied_behavior;
  event.timeout_ns = static_cast<std::int64_t>(record.timeout_ms) * rt::kNsPerMs;
  event.granted_ns = record.granted_ns;
  event.motors = record.motors;
  event.min_success_rate = record.min_command_success_rate;
  event.on_low_success_rate = record.on_low_success_rate;
  event.default_kp.fill(device::kNoGain);
  event.default_kd.fill(device::kNoGain);
  for (std::size_t i = 0; i < record.motor_ids.size(); ++i) {
    const auto joint = static_cast<std::size_t>(record.motor_ids[i]);
    if (!record.default_kp.empty()) event.default_kp[joint] = record.default_kp[i];
    if (!record.default_kd.empty()) event.default_kd[joint] = record.default_kd[i];
  }
  return event;
}

device::ControlEvent session_release_event(const session::SessionRecord& record, Behavior applied) {
  device::ControlEvent event;
  event.type = device::ControlEvent::Type::kSessionRelease;
  event.slot = record.slot;
  event.generation = record.generation;
  event.behavior = applied;
  return event;
}

}  // namespace robotd::service
