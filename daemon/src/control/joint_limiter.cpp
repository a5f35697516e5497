#include "control/joint_limiter.hpp"

#include <cmath>
#include <initializer_list>

namespace robotd::control {

double clamp(double value, double low, double high) noexcept {
  return value < low ? low : (value > high ? high : value);
}

namespace {

// How far a setpoint moving at `speed` still travels when it brakes by a·dt every period
// from the next one on: (v − a·dt)·dt + (v − 2a·dt)·dt + … while that is positive.
double braking_distance(double speed, const MotionLimits& limits, double dt_s) noexcept {
  const double quantum = limits.acceleration_max * dt_s;
  const double steps = std::floor(speed / quantum);
  return dt_s * (steps * speed - quantum * steps * (steps + 1) / 2);
}

}  // namespace

double stopping_speed(double distance, const MotionLimits& limits, double dt_s) noexcept {
  if (!(distance > 0)) return 0;
  // The largest v with v·dt + braking_distance(v) <= distance. With n full braking steps
  // (v in [n·q, (n+1)·q), q = a·dt) that is distance/dt = (n+1)·v − q·n·(n+1)/2, so v follows
  // from n; the continuous √(2·a·d) finds n to within one.
  const double quantum = limits.acceleration_max * dt_s;
  const double span = distance / dt_s;
  const double estimate = 0.5 * (std::sqrt(quantum * quantum + 8.0 * limits.acceleration_max * distance) - quantum);
  const double guess = std::floor(estimate / quantum);
  for (const double steps : {guess, guess - 1, guess + 1}) {
    if (steps < 0) continue;
    const double speed = (span + quantum * steps * (steps + 1) / 2) / (steps + 1);
    if (speed >= steps * quantum * (1 - 1e-12) && speed <= (steps + 1) * quantum * (1 + 1e-12)) return speed;
  }
  return std::fmin(estimate, span);
}

double velocity_within_limits(double velocity, double position, const MotionLimits& limits, double dt_s) noexcept {
  const double up = std::fmin(limits.velocity_max, stopping_speed(limits.position_max - position, limits, dt_s));
  const double down = std::fmin(limits.velocity_max, stopping_speed(position - limits.position_min, limits, dt_s));
  return clamp(velocity, -down, up);
}

double braking_point(const LimiterState& state, const MotionLimits& limits, double dt_s) noexcept {
  const double distance = braking_distance(std::fabs(state.velocity), limits, dt_s);
  const double point = state.position + (state.velocity >= 0 ? distance : -distance);
  // A setpoint outside a limit holds where it is; inside, it never brakes beyond a limit.
  const double low = std::fmin(limits.position_min, state.position);
  const double high = std::fmax(limits.position_max, state.position);
  return clamp(point, low, high);
}

LimiterState limit_step(LimiterState state, double target, double target_velocity, const MotionLimits& limits,
                        double dt_s) noexcept {
  const double vmax = limits.velocity_max;
  const double amax = limits.acceleration_max;
  const double inside_target = clamp(target, limits.position_min, limits.position_max);
  // A target held at a limit does not move on with the stream.
  target_velocity = inside_target == target ? clamp(target_velocity, -vmax, vmax) : 0.0;
  target = inside_target;

  const double error = target - state.position;
  const double distance = std::fabs(error);
  const double direction = error >= 0 ? 1.0 : -1.0;
  // The fastest approach speed from which we can still stop on the target.
  const double approach_speed = stopping_speed(distance, limits, dt_s);
  double velocity_goal = clamp(target_velocity + direction * approach_speed, -vmax, vmax);
  // Never faster toward a position limit than what stops on it.
  velocity_goal = velocity_within_limits(velocity_goal, state.position, limits, dt_s);
  const double max_delta_v = amax * dt_s;
  const double velocity = state.velocity + clamp(velocity_goal - state.velocity, -max_delta_v, max_delta_v);

  LimiterState next{state.position + velocity * dt_s, velocity};
  // The last line of defence, for a setpoint too fast to stop in time (or a rounding error's
  // worth past the limit): it stops on the limit, never further outside than it was, and its
  // velocity is the step it really took.
  const double low = std::fmin(limits.position_min, state.position);
  const double high = std::fmax(limits.position_max, state.position);
  if (next.position < low || next.position > high) {
    next.position = clamp(next.position, low, high);
    next.velocity = (next.position - state.position) / dt_s;
  }
  return next;
}

}  // namespace robotd::control
