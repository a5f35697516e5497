// The fallback a device really performs: ZERO_TORQUE → DAMPING → KEEP, each step taken only
// when the device cannot do the one asked for.
#include "control/behavior_map.hpp"

#include <gtest/gtest.h>

namespace robotd::control {
namespace {

constexpr BehaviorSupport support(bool damping, bool zero_torque) {
  BehaviorSupport s;
  s.damping = damping;
  s.zero_torque = zero_torque;
  return s;
}

constexpr BehaviorSupport kPositionOnly = support(false, false);
constexpr BehaviorSupport kDampingOnly = support(true, false);
constexpr BehaviorSupport kZeroTorqueOnly = support(false, true);
constexpr BehaviorSupport kBoth = support(true, true);

TEST(BehaviorMap, KeepIsKeptOnEveryDevice) {
  EXPECT_EQ(applied_behavior(Behavior::kKeep, kPositionOnly), Behavior::kKeep);
  EXPECT_EQ(applied_behavior(Behavior::kKeep, kDampingOnly), Behavior::kKeep);
  EXPECT_EQ(applied_behavior(Behavior::kKeep, kZeroTorqueOnly), Behavior::kKeep);
  EXPECT_EQ(applied_behavior(Behavior::kKeep, kBoth), Behavior::kKeep);
}

TEST(BehaviorMap, DampingDampsWhereSupportedAndOtherwiseKeeps) {
  EXPECT_EQ(applied_behavior(Behavior::kDamping, kPositionOnly), Behavior::kKeep);
  EXPECT_EQ(applied_behavior(Behavior::kDamping, kDampingOnly), Behavior::kDamping);
  // Letting go is not a substitute for damping: it is the less safe of the two.
  EXPECT_EQ(applied_behavior(Behavior::kDamping, kZeroTorqueOnly), Behavior::kKeep);
  EXPECT_EQ(applied_behavior(Behavior::kDamping, kBoth), Behavior::kDamping);
}

TEST(BehaviorMap, ZeroTorqueFallsBackToDampingThenToKeep) {
  EXPECT_EQ(applied_behavior(Behavior::kZeroTorque, kPositionOnly), Behavior::kKeep);
  EXPECT_EQ(applied_behavior(Behavior::kZeroTorque, kDampingOnly), Behavior::kDamping);
  EXPECT_EQ(applied_behavior(Behavior::kZeroTorque, kZeroTorqueOnly), Behavior::kZeroTorque);
  EXPECT_EQ(applied_behavior(Behavior::kZeroTorque, kBoth), Behavior::kZeroTorque);
}

}  // namespace
}  // namespace robotd::control
