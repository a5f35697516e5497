#include "joint_profile.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::piper::sim {
namespace {

constexpr double kMinAcceleration = 1e-6;  // a zero limit would divide by zero; it means "barely"

}  // namespace

void step_toward(double target_rad, const ProfileLimits& limits, double dt_s, ProfileState& state) noexcept {
  if (!(dt_s > 0)) return;
  const double acceleration = std::max(limits.max_acceleration_rad_s2, kMinAcceleration);
  const double max_velocity = std::max(limits.max_velocity_rad_s, 0.0);
  const double distance = target_rad - state.position_rad;
  // The fastest velocity from which the joint still stops on the target: v² = 2·a·d.
  const double desired =
      std::copysign(std::min(max_velocity, std::sqrt(2.0 * acceleration * std::abs(distance))), distance);
  const double change = std::clamp(desired - state.velocity_rad_s, -acceleration * dt_s, acceleration * dt_s);
  const double velocity = state.velocity_rad_s + change;
  const double position = state.position_rad + 0.5 * (state.velocity_rad_s + velocity) * dt_s;
  const bool crossed = (distance >= 0 && position >= target_rad) || (distance <= 0 && position <= target_rad);
  if (crossed) {
    state = ProfileState{.position_rad = target_rad, .velocity_rad_s = 0};
  } else {
    state = ProfileState{.position_rad = position, .velocity_rad_s = velocity};
  }
}

void step_to_rest(double max_acceleration_rad_s2, double dt_s, ProfileState& state) noexcept {
  if (!(dt_s > 0)) return;
  const double brake = std::max(max_acceleration_rad_s2, kMinAcceleration) * dt_s;
  const double velocity =
      std::abs(state.velocity_rad_s) <= brake ? 0.0 : state.velocity_rad_s - std::copysign(brake, state.velocity_rad_s);
  state.position_rad += 0.5 * (state.velocity_rad_s + velocity) * dt_s;
  state.velocity_rad_s = velocity;
}

double stopping_position(const ProfileState& state, double max_acceleration_rad_s2) noexcept {
  const double acceleration = std::max(max_acceleration_rad_s2, kMinAcceleration);
  return state.position_rad + state.velocity_rad_s * std::abs(state.velocity_rad_s) / (2.0 * acceleration);
}

}  // namespace robotd::piper::sim
