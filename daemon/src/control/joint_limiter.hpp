// Rate limiting of a joint's position setpoint: whatever the target, the setpoint moves with
// |velocity| <= velocity_max and |acceleration| <= acceleration_max, brakes in time to stop
// on the target, and never crosses a position limit: it brakes in time to stop on it. A far
// target becomes a smooth trapezoidal move instead of a jump. A setpoint that starts outside
// the limits (a joint measured beyond a narrowed limit) comes back inside under the same
// velocity and acceleration limits and never moves further out. Pure functions: no state
// beyond what is passed in.
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

/// The fastest speed for this period from which the loop, braking by acceleration_max·dt
/// every period after it, still stops within `distance`, exactly (0 for a distance <= 0).
double stopping_speed(double distance, const MotionLimits& limits, double dt_s) noexcept;

/// Where a setpoint moving at state.velocity comes to rest when it brakes as hard as the
/// limits allow (never beyond a position limit it has not already crossed).
double braking_point(const LimiterState& state, const MotionLimits& limits, double dt_s) noexcept;

/// `velocity` limited to what can still stop at the position limits from `position`: at
/// most velocity_max, and never outward when `position` is outside a limit.
double velocity_within_limits(double velocity, double position, const MotionLimits& limits, double dt_s) noexcept;

double clamp(double value, double low, double high) noexcept;

}  // namespace robotd::control
