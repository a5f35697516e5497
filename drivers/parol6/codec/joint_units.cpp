// The PAROL6 joint table of parol6_serial.md §10 and the microstep ⇄ SI conversions, computed
// with the same floating-point operations, in the same order, as the vendor's Python API
// (PCrnjak/PAROL6-python-API parol6/config.py) so that robotd sends the step it would send;
// tests/conformance/parol6 checks them against both vendor codebases.
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
    joint(6.4, -123.046875, 123.046875, 10240, 15000),             // J1 base, 96/15
    joint(20.0, -145.0088, -3.375, -32000, 25000),                 // J2 shoulder
    joint(20.0 * (38.0 / 42.0), 107.866, 287.8675, 57905, 32000),  // J3 elbow
    joint(4.0, -105.46975, 105.46975, 0, 10000),                   // J4 wrist 1
    joint(4.0, -90.0, 90.0, 0, 10000),                             // J5 wrist 2
    joint(10.0, 0.0, 360.0, 32000, 27000),                         // J6 wrist 3
}};

/// The API's radian_per_step_constant: one microstep at the motor.
constexpr double kRadianPerStep = 2.0 * std::numbers::pi / kMicrostepsPerMotorRevolution;

double gear_ratio(int joint) { return kJointUnits[static_cast<std::size_t>(joint)].gear_ratio; }

enum class Rounding : std::uint8_t {
  kNearestTiesToEven,  // np.rint, the API's positions
  kTowardZero,         // np.int32(x) / int(x), both hosts' speeds
};

/// `value` as an int32 the way `rounding` says, saturated (NaN gives 0) where the hosts' casts
/// would be undefined.
std::int32_t to_int32(double value, Rounding rounding) {
  constexpr double kLowest = std::numeric_limits<std::int32_t>::lowest();
  constexpr double kHighest = std::numeric_limits<std::int32_t>::max();
  if (std::isnan(value)) return 0;
  if (value <= kLowest) return std::numeric_limits<std::int32_t>::lowest();
  if (value >= kHighest) return std::numeric_limits<std::int32_t>::max();
  // std::nearbyint rounds ties to even in the default rounding mode, which robotd never changes.
  return static_cast<std::int32_t>(rounding == Rounding::kNearestTiesToEven ? std::nearbyint(value)
                                                                            : std::trunc(value));
}

}  // namespace

const std::array<JointUnits, kJoints>& joint_units() { return kJointUnits; }

double steps_per_rad(int joint) { return gear_ratio(joint) / kRadianPerStep; }

// config.py steps_to_rad: (steps × radian_per_step) / ratio.
double steps_to_rad(int joint, double steps) { return steps * kRadianPerStep / gear_ratio(joint); }

// config.py rad_to_steps, the conversion of every API motion command: rad × (1 / radian_per_step),
// × ratio, np.rint. (Its rad_to_steps_scalar divides instead and can land on the other side of a
// half step; only the API's warm-up calls it.)
std::int32_t rad_to_steps(int joint, double rad) {
  return to_int32(rad * (1.0 / kRadianPerStep) * gear_ratio(joint), Rounding::kNearestTiesToEven);
}

// config.py speed_steps_to_rad: (steps/s × radian_per_step) / ratio.
double steps_per_s_to_rad_per_s(int joint, double steps_per_s) {
  return steps_per_s * kRadianPerStep / gear_ratio(joint);
}

// config.py speed_rad_to_steps and the commander's int(SPEED_RAD2STEP(...)): (rad/s / radian_per_step)
// × ratio, truncated toward zero.
std::int32_t rad_per_s_to_steps_per_s(int joint, double rad_per_s) {
  return to_int32(rad_per_s / kRadianPerStep * gear_ratio(joint), Rounding::kTowardZero);
}

}  // namespace robotd::parol6
