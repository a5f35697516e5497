#include "joint_dynamics.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace robotd::sim {
namespace {

constexpr double kTickS = 1e-3;

// The sim's default joint: inertia 0.05 kg·m², viscous damping 0.5 N·m·s/rad, stops at ±3 rad.
const JointPhysics kJoint{};

JointState run(const JointPhysics& physics, const MotorLaw& law, double external_torque_nm, double seconds,
               JointState state = {}) {
  const int ticks = static_cast<int>(std::lround(seconds / kTickS));
  for (int i = 0; i < ticks; ++i) step_joint(physics, law, external_torque_nm, kTickS, state);
  return state;
}

TEST(SimJointDynamics, PositionServoConvergesToTarget) {
  const MotorLaw servo{.kp = 100, .kd = 5, .position_rad = 1.2};
  const JointState state = run(kJoint, servo, 0, 1.0);
  EXPECT_NEAR(state.position_rad, 1.2, 1e-4);
  EXPECT_NEAR(state.velocity_rad_s, 0, 1e-3);
  EXPECT_NEAR(state.motor_torque_nm, 0, 1e-2);
}

TEST(SimJointDynamics, PositionServoUnderLoadSettlesWithProportionalError) {
  const MotorLaw servo{.kp = 100, .kd = 5, .position_rad = 0.5};
  const JointState state = run(kJoint, servo, -2.0, 1.0);
  EXPECT_NEAR(state.position_rad, 0.5 - 2.0 / 100, 1e-4);
  EXPECT_NEAR(state.motor_torque_nm, 2.0, 1e-2);
}

TEST(SimJointDynamics, DampingUnderExternalTorqueSinksAtTorqueOverTotalDamping) {
  const MotorLaw damping{.kd = 5};
  const JointState settled = run(kJoint, damping, -2.0, 0.2);
  const double terminal_velocity = -2.0 / (5 + 0.5);
  EXPECT_NEAR(settled.velocity_rad_s, terminal_velocity, 1e-3 * std::abs(terminal_velocity));
  const JointState later = run(kJoint, damping, -2.0, 0.5, settled);
  EXPECT_NEAR(later.position_rad - settled.position_rad, terminal_velocity * 0.5, 1e-3);
  EXPECT_NEAR(later.motor_torque_nm, -5 * terminal_velocity, 1e-3);
}

TEST(SimJointDynamics, ZeroTorqueUnderExternalTorqueFallsToTheHardStop) {
  const JointState state = run(kJoint, MotorLaw{}, -2.0, 2.0);
  EXPECT_EQ(state.position_rad, kJoint.position_min_rad);
  EXPECT_EQ(state.velocity_rad_s, 0);
  EXPECT_EQ(state.motor_torque_nm, 0);
}

TEST(SimJointDynamics, MotorTorqueIsClampedToEffortMax) {
  JointPhysics weak = kJoint;
  weak.effort_max_nm = 10;
  JointState state;
  step_joint(weak, MotorLaw{.kp = 500, .position_rad = 2.0}, 0, kTickS, state);
  EXPECT_EQ(state.motor_torque_nm, 10);
  state = JointState{};
  step_joint(weak, MotorLaw{.torque_nm = -25}, 0, kTickS, state);
  EXPECT_EQ(state.motor_torque_nm, -10);
  EXPECT_LT(state.velocity_rad_s, 0);
}

TEST(SimJointDynamics, ClampedTorqueLimitsAcceleration) {
  JointPhysics weak = kJoint;
  weak.effort_max_nm = 10;
  weak.damping_nm_s_rad = 0;
  JointState state;
  step_joint(weak, MotorLaw{.kp = 500, .position_rad = 2.0}, 0, kTickS, state);
  EXPECT_NEAR(state.velocity_rad_s, 10 / weak.inertia_kg_m2 * kTickS, 1e-9);
}

TEST(SimJointDynamics, HardStopHoldsAFarTargetAtTheLimit) {
  const MotorLaw far_target{.kp = 100, .kd = 5, .position_rad = 10.0};
  const JointState state = run(kJoint, far_target, 0, 2.0);
  EXPECT_EQ(state.position_rad, kJoint.position_max_rad);
  EXPECT_EQ(state.velocity_rad_s, 0);
  EXPECT_EQ(state.motor_torque_nm, kJoint.effort_max_nm);
}

TEST(SimJointDynamics, JointLeavesTheHardStopWhenPushedInward) {
  JointState at_stop{.position_rad = kJoint.position_min_rad};
  step_joint(kJoint, MotorLaw{.torque_nm = 5}, 0, kTickS, at_stop);
  EXPECT_GT(at_stop.position_rad, kJoint.position_min_rad);
  EXPECT_GT(at_stop.velocity_rad_s, 0);
}

TEST(SimJointDynamics, StiffGainsOnASmallInertiaStayStable) {
  JointPhysics light = kJoint;
  light.inertia_kg_m2 = 1e-4;
  const JointState state = run(light, MotorLaw{.kp = 500, .kd = 50, .position_rad = 0.3}, 0, 2.0);
  EXPECT_NEAR(state.position_rad, 0.3, 1e-6);
  EXPECT_NEAR(state.velocity_rad_s, 0, 1e-6);
}

TEST(SimJointDynamics, StepLongerThanMaxStepAdvancesOnlyMaxStep) {
  JointState long_step;
  step_joint(kJoint, MotorLaw{}, -2.0, 1.0, long_step);
  JointState max_step;
  step_joint(kJoint, MotorLaw{}, -2.0, kMaxStepS, max_step);
  EXPECT_LT(long_step.position_rad, 0);
  EXPECT_EQ(long_step.position_rad, max_step.position_rad);
  EXPECT_EQ(long_step.velocity_rad_s, max_step.velocity_rad_s);
}

TEST(SimJointDynamics, NonPositiveStepLeavesTheStateUnchanged) {
  JointState state{.position_rad = 0.4, .velocity_rad_s = 1.0, .motor_torque_nm = 2.0};
  step_joint(kJoint, MotorLaw{.torque_nm = 5}, -2.0, 0, state);
  step_joint(kJoint, MotorLaw{.torque_nm = 5}, -2.0, -1e-3, state);
  EXPECT_EQ(state.position_rad, 0.4);
  EXPECT_EQ(state.velocity_rad_s, 1.0);
  EXPECT_EQ(state.motor_torque_nm, 2.0);
}

}  // namespace
}  // namespace robotd::sim
