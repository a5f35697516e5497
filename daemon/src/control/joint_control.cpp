#include "control/joint_control.hpp"

#include <algorithm>

namespace robotd::control {

void begin_tracking(JointControl& joint, const driver::JointFeedback& measured, const MotionLimits& limits,
                    double dt_s) noexcept {
  if (joint.mode == JointMode::kTrack) return;
  joint.mode = JointMode::kTrack;
  if (joint.setpoint_written) return;
  joint.setpoint = LimiterState{measured.position_rad,
                                velocity_within_limits(measured.velocity_rad_s, measured.position_rad, limits, dt_s)};
}

void hold_position(JointControl& joint, const driver::JointFeedback& measured, Gains gains, const MotionLimits& limits,
                   double dt_s) noexcept {
  if (joint.mode == JointMode::kTrack || joint.setpoint_written) {
    joint.mode = JointMode::kTrack;
    joint.target_position = braking_point(joint.setpoint, limits, dt_s);
  } else {
    joint.mode = JointMode::kTrack;
    joint.track_kind = driver::JointCommandKind::kPosition;
    joint.setpoint = LimiterState{measured.position_rad, 0};
    joint.target_position = measured.position_rad;
  }
  joint.target_velocity = 0;
  joint.extrapolate_ns = 0;
  joint.kp = gains.kp;
  joint.kd = gains.kd;
  joint.torque_nm = 0;
}

void hold_measured(JointControl& joint, const driver::JointFeedback& measured, Gains gains) noexcept {
  joint.mode = JointMode::kTrack;
  joint.track_kind = driver::JointCommandKind::kPosition;
  joint.setpoint = LimiterState{measured.position_rad, 0};
  joint.target_position = measured.position_rad;
  joint.target_velocity = 0;
  joint.extrapolate_ns = 0;
  joint.kp = gains.kp;
  joint.kd = gains.kd;
  joint.torque_nm = 0;
}

void apply_behavior(JointControl& joint, Behavior behavior, const driver::JointFeedback& measured, Gains gains,
                    const MotionLimits& limits, double dt_s) noexcept {
  switch (behavior) {
    case Behavior::kKeep:
      hold_position(joint, measured, gains, limits, dt_s);
      return;
    case Behavior::kDamping:
      joint.mode = JointMode::kDamping;
      joint.kd = gains.kd;
      return;
    case Behavior::kZeroTorque:
      joint.mode = JointMode::kZeroTorque;
      return;
  }
}

driver::JointCommand joint_output(JointControl& joint, const driver::JointFeedback& measured,
                                  const MotionLimits& limits, double dt_s, std::int64_t now_ns) noexcept {
  driver::JointCommand out;
  joint.setpoint_written = joint.mode == JointMode::kTrack;
  switch (joint.mode) {
    case JointMode::kIdle:
      return out;
    case JointMode::kTrack: {
      // Between streamed targets, extrapolate along the stream's velocity (first-order hold).
      const std::int64_t age_ns = std::clamp<std::int64_t>(now_ns - joint.target_time_ns, 0, joint.extrapolate_ns);
      const bool extrapolating = now_ns - joint.target_time_ns < joint.extrapolate_ns;
      const double target = joint.target_position + joint.target_velocity * static_cast<double>(age_ns) * 1e-9;
      joint.setpoint = limit_step(joint.setpoint, target, extrapolating ? joint.target_velocity : 0.0, limits, dt_s);
      out.kind = joint.track_kind;
      out.position_rad = joint.setpoint.position;
      out.velocity_rad_s = joint.setpoint.velocity;
      out.kp = joint.kp;
      out.kd = joint.kd;
      out.torque_nm = joint.torque_nm;
      return out;
    }
    case JointMode::kTorque:
      out.kind = driver::JointCommandKind::kImpedance;
      out.position_rad = measured.position_rad;
      out.torque_nm = joint.torque_nm;
      return out;
    case JointMode::kDamping:
      out.kind = driver::JointCommandKind::kImpedance;
      out.position_rad = measured.position_rad;
      out.kd = joint.kd;
      return out;
    case JointMode::kZeroTorque:
      out.kind = driver::JointCommandKind::kImpedance;
      out.position_rad = measured.position_rad;
      return out;
  }
  return out;
}

}  // namespace robotd::control
