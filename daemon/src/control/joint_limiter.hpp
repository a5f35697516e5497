// Rate limiting of a joint's position setpoint: whatever the target, the setpoint moves with
// |velocity| <= velocity_max and |acceleration| <= acceleration_max, brakes in time to stop
// on the target, and stays inside the position limits. A far target becomes a smooth
// trapezoidal move instead of a jump. Pure functions: no state beyond what is passed in.
#pragma once

namespace robotd::control {

struct LimiterState {
  double position = 0;
  double velocity = 0;
};

struct MotionLimits {
  double position_min = 0;
  double position_max = 0;
  double velocity_max = 0;
  double acceleration_max = 0;
};

/// Advances `state` by one period `dt_s` toward `target` (moving itself at `target_velocity`,
/// the feed-forward of a streamed trajectory; 0 for a fixed target).
LimiterState limit_step(LimiterState state, double target, double target_velocity, const MotionLimits& limits,
                        double dt_s) noexcept;

double clamp(double value, double low, double high) noexcept;

}  // namespace robotd::control
