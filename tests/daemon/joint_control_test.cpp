// What the loop does with one joint: start from where it is measured, hold without jumping,
// apply each fallback behaviour, and turn the joint's mode into the command a driver gets.
#include "control/joint_control.hpp"

#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include "loop_tick.hpp"

namespace robotd::control {
namespace {

using driver::JointCommandKind;

constexpr std::int64_t kMsNs = 1'000'000;

driver::JointFeedback measured(double position, double velocity = 0.0) {
  driver::JointFeedback feedback;
  feedback.position_rad = position;
  feedback.velocity_rad_s = velocity;
  return feedback;
}

MotionLimits motion_limits() {
  MotionLimits l;
  l.position_min = -2.0;
  l.position_max = 2.0;
  l.velocity_max = 1.0;
  l.acceleration_max = 10.0;
  return l;
}

// A joint tracking toward 1.5 rad, its setpoint part-way there and moving.
JointControl tracking_joint() {
  JointControl joint;
  joint.mode = JointMode::kTrack;
  joint.track_kind = JointCommandKind::kImpedance;
  joint.setpoint = LimiterState{0.7, 0.3};
  joint.target_position = 1.5;
  joint.target_velocity = 0.5;
  joint.extrapolate_ns = 10 * kMsNs;
  joint.kp = 30.0;
  joint.kd = 3.0;
  joint.torque_nm = 1.0;
  return joint;
}

TEST(JointControl, BeginTrackingStartsFromTheMeasuredState) {
  JointControl joint;
  begin_tracking(joint, measured(0.4, 0.2), motion_limits(), kDt);
  EXPECT_EQ(joint.mode, JointMode::kTrack);
  EXPECT_DOUBLE_EQ(joint.setpoint.position, 0.4);
  EXPECT_DOUBLE_EQ(joint.setpoint.velocity, 0.2);
}

TEST(JointControl, BeginTrackingClampsTheMeasuredVelocityToTheLimit) {
  JointControl joint;
  begin_tracking(joint, measured(0.4, -3.0), motion_limits(), kDt);
  EXPECT_DOUBLE_EQ(joint.setpoint.velocity, -1.0);
}

TEST(JointControl, BeginTrackingNearALimitSeedsOnlyAVelocityThatStillStopsOnIt) {
  // 1 mm from the upper limit, moving at 0.9 rad/s toward it: 10 rad/s² cannot stop that in
  // 1 mm, so the setpoint starts at the speed it can still stop from.
  JointControl joint;
  begin_tracking(joint, measured(1.999, 0.9), motion_limits(), kDt);
  EXPECT_GT(joint.setpoint.velocity, 0.0);
  EXPECT_LT(joint.setpoint.velocity, 0.15);
  EXPECT_DOUBLE_EQ(joint.setpoint.velocity, velocity_within_limits(0.9, 1.999, motion_limits(), kDt));
}

TEST(JointControl, BeginTrackingOutsideALimitNeverSeedsAVelocityOutward) {
  JointControl joint;
  begin_tracking(joint, measured(2.6, 0.4), motion_limits(), kDt);
  EXPECT_DOUBLE_EQ(joint.setpoint.position, 2.6);
  EXPECT_DOUBLE_EQ(joint.setpoint.velocity, 0.0);
}

TEST(JointControl, BeginTrackingContinuesTheSetpointTheLastCommandCarried) {
  // Released into DAMPING and taken by a new session within one tick: the damping was never
  // written, so the new session continues from the setpoint the driver last got.
  JointControl joint = tracking_joint();
  joint.setpoint_written = true;
  joint.mode = JointMode::kDamping;
  begin_tracking(joint, measured(0.4, 0.0), motion_limits(), kDt);
  EXPECT_EQ(joint.mode, JointMode::kTrack);
  EXPECT_DOUBLE_EQ(joint.setpoint.position, 0.7);
  EXPECT_DOUBLE_EQ(joint.setpoint.velocity, 0.3);
}

TEST(JointControl, BeginTrackingIsANoOpWhenAlreadyTracking) {
  JointControl joint = tracking_joint();
  begin_tracking(joint, measured(0.4, 0.0), motion_limits(), kDt);
  EXPECT_DOUBLE_EQ(joint.setpoint.position, 0.7);
  EXPECT_DOUBLE_EQ(joint.setpoint.velocity, 0.3);
}

TEST(JointControl, HoldPositionWhileTrackingBrakesAtOnceAndDropsTheClientsGainsAndTorque) {
  JointControl joint = tracking_joint();  // at 0.7 rad, moving at 0.3 rad/s, kp 30, 1 N·m feed-forward
  hold_position(joint, measured(0.4), Gains{50.0, 2.0}, motion_limits(), kDt);
  EXPECT_EQ(joint.mode, JointMode::kTrack);
  // Braking from the next step on: 0.29, 0.28, … rad/s, each for 1 ms.
  double distance = 0;
  for (int k = 1; k < 30; ++k) distance += (0.3 - 10.0 * kDt * k) * kDt;
  EXPECT_NEAR(joint.target_position, 0.7 + distance, 1e-12);
  EXPECT_DOUBLE_EQ(joint.target_velocity, 0.0);
  EXPECT_EQ(joint.extrapolate_ns, 0);
  EXPECT_DOUBLE_EQ(joint.setpoint.position, 0.7);
  EXPECT_DOUBLE_EQ(joint.kp, 50.0);
  EXPECT_DOUBLE_EQ(joint.kd, 2.0);
  EXPECT_DOUBLE_EQ(joint.torque_nm, 0.0);
}

TEST(JointControl, HeldJointDeceleratesToRestWithoutTurningBack) {
  JointControl joint = tracking_joint();
  hold_position(joint, measured(0.4), Gains{50.0, 2.0}, motion_limits(), kDt);
  double previous_velocity = 0.3;
  double position = 0.7;
  for (std::int64_t ms = 1; ms <= 100; ++ms) {
    const driver::JointCommand out = joint_output(joint, measured(0.4), motion_limits(), kDt, ms * kMsNs);
    ASSERT_GE(out.velocity_rad_s, 0.0) << "ms " << ms;
    ASSERT_LE(out.velocity_rad_s, previous_velocity + 1e-12) << "ms " << ms;
    ASSERT_GE(out.position_rad, position - 1e-15) << "ms " << ms;
    previous_velocity = out.velocity_rad_s;
    position = out.position_rad;
  }
  EXPECT_DOUBLE_EQ(previous_velocity, 0.0);
  EXPECT_NEAR(position, joint.target_position, 1e-12);
}

TEST(JointControl, HoldPositionWhenNotTrackingHoldsTheMeasuredPositionWithTheFallbackGains) {
  JointControl joint;
  joint.mode = JointMode::kDamping;
  joint.torque_nm = 2.0;
  joint.track_kind = JointCommandKind::kImpedance;
  hold_position(joint, measured(0.4, 0.9), Gains{50.0, 2.0}, motion_limits(), kDt);
  EXPECT_EQ(joint.mode, JointMode::kTrack);
  EXPECT_EQ(joint.track_kind, JointCommandKind::kPosition);
  EXPECT_DOUBLE_EQ(joint.target_position, 0.4);
  EXPECT_DOUBLE_EQ(joint.setpoint.position, 0.4);
  EXPECT_DOUBLE_EQ(joint.setpoint.velocity, 0.0);
  EXPECT_DOUBLE_EQ(joint.kp, 50.0);
  EXPECT_DOUBLE_EQ(joint.kd, 2.0);
  EXPECT_DOUBLE_EQ(joint.torque_nm, 0.0);
}

TEST(JointControl, HoldMeasuredDropsTheOldTargetAndSetpoint) {
  JointControl joint = tracking_joint();
  hold_measured(joint, measured(0.4, 0.6), Gains{20.0, 1.0});
  EXPECT_EQ(joint.mode, JointMode::kTrack);
  EXPECT_EQ(joint.track_kind, JointCommandKind::kPosition);
  EXPECT_DOUBLE_EQ(joint.setpoint.position, 0.4);
  EXPECT_DOUBLE_EQ(joint.setpoint.velocity, 0.0);
  EXPECT_DOUBLE_EQ(joint.target_position, 0.4);
  EXPECT_DOUBLE_EQ(joint.target_velocity, 0.0);
  EXPECT_EQ(joint.extrapolate_ns, 0);
  EXPECT_DOUBLE_EQ(joint.kp, 20.0);
  EXPECT_DOUBLE_EQ(joint.kd, 1.0);
  EXPECT_DOUBLE_EQ(joint.torque_nm, 0.0);
}

TEST(JointControl, KeepBehaviourHoldsWhereTheJointComesToRest) {
  JointControl joint = tracking_joint();
  apply_behavior(joint, Behavior::kKeep, measured(0.4), Gains{50.0, 2.0}, motion_limits(), kDt);
  EXPECT_EQ(joint.mode, JointMode::kTrack);
  EXPECT_DOUBLE_EQ(joint.target_position, braking_point(LimiterState{0.7, 0.3}, motion_limits(), kDt));
  EXPECT_DOUBLE_EQ(joint.torque_nm, 0.0);
}

TEST(JointControl, DampingBehaviourCommandsDampingAtTheMeasuredPosition) {
  JointControl joint = tracking_joint();
  apply_behavior(joint, Behavior::kDamping, measured(0.4), Gains{50.0, 2.5}, motion_limits(), kDt);
  EXPECT_EQ(joint.mode, JointMode::kDamping);
  const driver::JointCommand out = joint_output(joint, measured(0.45), motion_limits(), kDt, 0);
  EXPECT_EQ(out.kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(out.position_rad, 0.45);
  EXPECT_DOUBLE_EQ(out.kp, 0.0);
  EXPECT_DOUBLE_EQ(out.kd, 2.5);
  EXPECT_DOUBLE_EQ(out.torque_nm, 0.0);
}

TEST(JointControl, ZeroTorqueBehaviourLetsGo) {
  JointControl joint = tracking_joint();
  apply_behavior(joint, Behavior::kZeroTorque, measured(0.4), Gains{50.0, 2.0}, motion_limits(), kDt);
  EXPECT_EQ(joint.mode, JointMode::kZeroTorque);
  const driver::JointCommand out = joint_output(joint, measured(0.45), motion_limits(), kDt, 0);
  EXPECT_EQ(out.kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(out.kp, 0.0);
  EXPECT_DOUBLE_EQ(out.kd, 0.0);
  EXPECT_DOUBLE_EQ(out.torque_nm, 0.0);
}

TEST(JointControl, IdleJointCommandsNothing) {
  JointControl joint;
  const driver::JointCommand out = joint_output(joint, measured(0.4), motion_limits(), kDt, 0);
  EXPECT_EQ(out.kind, JointCommandKind::kNone);
}

TEST(JointControl, TorqueModeCommandsPureTorque) {
  JointControl joint;
  joint.mode = JointMode::kTorque;
  joint.torque_nm = -1.25;
  joint.kp = 30.0;  // gains of an earlier mode must not leak into pure torque
  joint.kd = 3.0;
  const driver::JointCommand out = joint_output(joint, measured(0.4), motion_limits(), kDt, 0);
  EXPECT_EQ(out.kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(out.kp, 0.0);
  EXPECT_DOUBLE_EQ(out.kd, 0.0);
  EXPECT_DOUBLE_EQ(out.torque_nm, -1.25);
  EXPECT_DOUBLE_EQ(out.position_rad, 0.4);
}

TEST(JointControl, TrackingCommandsTheLimitedSetpointWithTheJointsKindAndGains) {
  JointControl joint;
  begin_tracking(joint, measured(0.0), motion_limits(), kDt);
  joint.target_position = 1.0;
  joint.kp = 40.0;
  joint.kd = 4.0;
  joint.track_kind = JointCommandKind::kImpedance;
  joint.torque_nm = 0.5;
  const driver::JointCommand first = joint_output(joint, measured(0.0), motion_limits(), kDt, 0);
  EXPECT_EQ(first.kind, JointCommandKind::kImpedance);
  EXPECT_DOUBLE_EQ(first.kp, 40.0);
  EXPECT_DOUBLE_EQ(first.kd, 4.0);
  EXPECT_DOUBLE_EQ(first.torque_nm, 0.5);
  // From rest the first step is one period of full acceleration, not a jump to the target.
  EXPECT_NEAR(first.velocity_rad_s, 10.0 * kDt, 1e-12);
  EXPECT_NEAR(first.position_rad, 10.0 * kDt * kDt, 1e-12);
  EXPECT_DOUBLE_EQ(joint.setpoint.position, first.position_rad);

  const driver::JointCommand second = joint_output(joint, measured(0.0), motion_limits(), kDt, kMsNs);
  EXPECT_GT(second.position_rad, first.position_rad);
  EXPECT_GT(second.velocity_rad_s, first.velocity_rad_s);
}

TEST(JointControl, ExtrapolationAlongTheStreamVelocityStopsAfterItsWindow) {
  JointControl joint;
  joint.mode = JointMode::kTrack;
  joint.setpoint = LimiterState{0.0, 0.5};
  joint.target_position = 0.0;
  joint.target_velocity = 0.5;
  joint.target_time_ns = 0;
  joint.extrapolate_ns = 20 * kMsNs;  // the stream promised a new target within 20 ms, then fell silent
  driver::JointCommand out;
  for (std::int64_t ms = 1; ms <= 10; ++ms) out = joint_output(joint, measured(0.0), motion_limits(), kDt, ms * kMsNs);
  EXPECT_NEAR(out.position_rad, 0.5 * 0.010, 1e-3);  // following the stream
  for (std::int64_t ms = 11; ms <= 2000; ++ms) {
    out = joint_output(joint, measured(0.0), motion_limits(), kDt, ms * kMsNs);
  }
  EXPECT_NEAR(out.position_rad, 0.5 * 0.020, 1e-9);  // stopped where the window ended
  EXPECT_NEAR(out.velocity_rad_s, 0.0, 1e-9);
}

}  // namespace
}  // namespace robotd::control
