#include "control/joint_limiter.hpp"

#include <cmath>

namespace robotd::control {

double clamp(double value, double low, double high) noexcept {
  return value < low ? low : (value > high ? high : value);
}

LimiterState limit_step(LimiterState state, double target, double target_velocity, const MotionLimits& limits,
                        double dt_s) noexcept {
  const double vmax = limits.velocity_max;
  const double amax = limits.acceleration_max;
  target = clamp(target, limits.position_min, limits.position_max);
  target_velocity = clamp(target_velocity, -vmax, vmax);

  const double error = target - state.position;
  const double distance = std::fabs(error);
  const double direction = error >= 0 ? 1.0 : -1.0;
  // The fastest approach speed from which we can still stop on the target with amax, but no
  // faster than what closes the gap in one period. The loop brakes in steps: v·dt this period,
  // then (v − amax·dt)·dt, … covers (v² + v·amax·dt) / (2·amax), so the speed is the root of
  // that, not the continuous √(2·amax·d), which stops about v·dt/2 past the target.
  const double brake_step = amax * dt_s;
  const double stopping_speed = 0.5 * (std::sqrt(brake_step * brake_step + 8.0 * amax * distance) - brake_step);
  const double approach_speed = std::fmin(stopping_speed, distance / dt_s);
  const double velocity_goal = clamp(target_velocity + direction * approach_speed, -vmax, vmax);
  const double max_delta_v = amax * dt_s;
  const double velocity = state.velocity + clamp(velocity_goal - state.velocity, -max_delta_v, max_delta_v);

  LimiterState next{state.position + velocity * dt_s, velocity};
  if (next.position < limits.position_min || next.position > limits.position_max) {
    next.position = clamp(next.position, limits.position_min, limits.position_max);
    next.velocity = 0;
  }
  return next;
}

}  // namespace robotd::control
