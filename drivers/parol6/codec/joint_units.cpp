// The PAROL6 joint table of parol6_serial.md §10 and the microstep ⇄ SI conversions both hosts
// use: rad = steps · 2π / 6400 / gear ratio.
#include "joint_units.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>

namespace robotd::parol6 {
namespace {

constexpr double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// The API's limits (§10.4): acceleration 3 × the hardware maximum speed, jog at 80 % of it.
constexpr double kAccelerationPerSpeed = 3.0;  // 1/s
constexpr double kJogFraction = 0.8;

constexpr JointUnits joint(double gear_ratio, double min_deg, double max_deg, std::int32_t standby_steps,
                           double max_speed_steps_s) {
  return JointUnits{.gear_ratio = gear_ratio,
                    .min_rad = radians(min_deg),
                    .max_rad = radians(max_deg),
                    .standby_steps = standby_steps,
                    .max_speed_steps_s = max_speed_steps_s,
                    .max_acceleration_steps_s2 = kAccelerationPerSpeed * max_speed_steps_s,
                    .jog_max_steps_s = kJogFraction * max_speed_steps_s};
}

// Gear ratios and limits (degrees) from §10.2, standby counters from §10.3 (the firmware's
// post-homing values: 90°, −90°, 180°, 0°, 0°, 180°), maximum speeds from §10.4.
constexpr std::array<JointUnits, kJoints> kJointUnits{{
    joint(6.4, -123.046875, 123.046875, 10240, 15000),           // J1 base, 96/15
    joint(20.0, -145.0088, -3.375, -32000, 25000),               // J2 shoulder
    joint(20.0 * 38.0 / 42.0, 107.866, 287.8675, 57905, 32000),  // J3 elbow
    joint(4.0, -105.46975, 105.46975, 0, 10000),                 // J4 wrist 1
    joint(4.0, -90.0, 90.0, 0, 10000),                           // J5 wrist 2
    joint(10.0, 0.0, 360.0, 32000, 27000),                       // J6 wrist 3
}};

/// `value` rounded to the nearest integer, saturated to int32 (NaN gives 0).
std::int32_t rounded(double value) {
  constexpr double kLowest = std::numeric_limits<std::int32_t>::lowest();
  constexpr double kHighest = std::numeric_limits<std::int32_t>::max();
  if (std::isnan(value)) return 0;
  if (value <= kLowest) return std::numeric_limits<std::int32_t>::lowest();
  if (value >= kHighest) return std::numeric_limits<std::int32_t>::max();
  return static_cast<std::int32_t>(std::lround(value));
}

}  // namespace

const std::array<JointUnits, kJoints>& joint_units() { return kJointUnits; }

double steps_per_rad(int joint) {
  return kMicrostepsPerMotorRevolution * kJointUnits[static_cast<std::size_t>(joint)].gear_ratio /
         (2.0 * std::numbers::pi);
}

double steps_to_rad(int joint, double steps) { return steps / steps_per_rad(joint); }

std::int32_t rad_to_steps(int joint, double rad) { return rounded(rad * steps_per_rad(joint)); }

double steps_per_s_to_rad_per_s(int joint, double steps_per_s) { return steps_per_s / steps_per_rad(joint); }

std::int32_t rad_per_s_to_steps_per_s(int joint, double rad_per_s) { return rounded(rad_per_s * steps_per_rad(joint)); }

}  // namespace robotd::parol6
