// What the loop does with one joint, tick by tick: idle, track a (rate-limited) position
// target, apply a torque, damp, or let go. Pure state and transitions, used only by the RT
// loop; no allocation.
#pragma once

#include <cstdint>

#include "control/joint_limiter.hpp"
#include "robotd/driver/types.hpp"
#include "robotd/messages.hpp"

namespace robotd::control {

enum class JointMode : std::uint8_t {
  kIdle,        // never commanded: nothing is sent for this joint
  kTrack,       // follow a position target through the rate limiter (POSITION and MIXED, and hold)
  kTorque,      // pure torque (TORQUE sessions)
  kDamping,     // kp = 0, kd = damping gain
  kZeroTorque,  // kp = kd = torque = 0
};

struct JointControl {
  JointMode mode = JointMode::kIdle;
  driver::JointCommandKind track_kind = driver::JointCommandKind::kPosition;
  double target_position = 0;
  double target_velocity = 0;       // feed-forward while the target is extrapolated
  std::int64_t target_time_ns = 0;  // when the target was valid
  std::int64_t extrapolate_ns = 0;  // extrapolate target_velocity for at most this long
  double kp = 0;
  double kd = 0;
  double torque_nm = 0;
  LimiterState setpoint;
  bool setpoint_written = false;  // the last command written for the joint carried this setpoint
};

struct Gains {
  double kp = 0;
  double kd = 0;
};

/// Starts tracking from the measured state, unless the joint already tracks or its last
/// written command carried a setpoint (then the setpoint continues, so successive targets
/// never jump). The measured velocity seeds the setpoint only as far as it can still stop at
/// the position limits.
void begin_tracking(JointControl& joint, const driver::JointFeedback& measured, const MotionLimits& limits,
                    double dt_s) noexcept;

/// KEEP: brakes as hard as the limits allow and holds where the setpoint comes to rest (a
/// joint without a live setpoint holds where it is measured). Holds with `gains` and no torque: a
/// client's gains and feed-forward torque end with its session.
void hold_position(JointControl& joint, const driver::JointFeedback& measured, Gains gains, const MotionLimits& limits,
                   double dt_s) noexcept;

/// Holds at the measured position, discarding any previous target (after e-stop, fault, recover).
void hold_measured(JointControl& joint, const driver::JointFeedback& measured, Gains gains) noexcept;

/// Applies a session's timeout / release behaviour, or the safe behaviour (already mapped to
/// what the device can do), with `gains` (the damping gain for DAMPING, the holding gains for KEEP).
void apply_behavior(JointControl& joint, Behavior behavior, const driver::JointFeedback& measured, Gains gains,
                    const MotionLimits& limits, double dt_s) noexcept;

/// The joint's command for this tick; advances the limiter for kTrack.
driver::JointCommand joint_output(JointControl& joint, const driver::JointFeedback& measured,
                                  const MotionLimits& limits, double dt_s, std::int64_t now_ns) noexcept;

}  // namespace robotd::control
