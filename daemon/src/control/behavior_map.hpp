// Which fallback a device can really perform. Position-only arms cannot damp or let go, so
// DAMPING and ZERO_TORQUE fall back to the nearest safe action the device supports:
// ZERO_TORQUE → DAMPING → KEEP (hold position). robotd reports the applied behaviour.
#pragma once

#include "robotd/messages.hpp"

namespace robotd::control {

struct BehaviorSupport {
  bool damping = false;
  bool zero_torque = false;
};

Behavior applied_behavior(Behavior requested, BehaviorSupport support) noexcept;

}  // namespace robotd::control
