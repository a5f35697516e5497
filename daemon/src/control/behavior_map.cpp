#include "control/behavior_map.hpp"

namespace robotd::control {

Behavior applied_behavior(Behavior requested, BehaviorSupport support) noexcept {
  if (requested == Behavior::kZeroTorque) {
    if (support.zero_torque) return Behavior::kZeroTorque;
    requested = Behavior::kDamping;
  }
  if (requested == Behavior::kDamping) {
    return support.damping ? Behavior::kDamping : Behavior::kKeep;
  }
  return Behavior::kKeep;
}

}  // namespace robotd::control
