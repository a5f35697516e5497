// How the simulated arm moves a joint to a position target without MIT: velocity limited,
// acceleration limited, decelerating so it stops at the target (a trapezoid, or a triangle for
// short moves). Pure math, no I/O.
#pragma once

namespace robotd::piper::sim {

struct ProfileLimits {
  double max_velocity_rad_s = 3.0;
  double max_acceleration_rad_s2 = 5.0;
};

struct ProfileState {
  double position_rad = 0;
  double velocity_rad_s = 0;
};

/// Advances `state` by `dt_s` toward `target_rad`. A step that would cross the target ends on
/// it at rest.
void step_toward(double target_rad, const ProfileLimits& limits, double dt_s, ProfileState& state) noexcept;

/// Advances `state` by `dt_s`, slowing to rest at `max_acceleration_rad_s2` (emergency stop).
void step_to_rest(double max_acceleration_rad_s2, double dt_s, ProfileState& state) noexcept;

/// Where a joint moving at `velocity_rad_s` comes to rest when it brakes at `max_acceleration_rad_s2`.
double stopping_position(const ProfileState& state, double max_acceleration_rad_s2) noexcept;

}  // namespace robotd::piper::sim
