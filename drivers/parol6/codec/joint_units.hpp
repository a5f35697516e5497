// PAROL6 joints in the board's units: microsteps (200 full steps × 32 microsteps per motor
// revolution) through each joint's gearbox (spec §10). steps = deg / 0.05625 × ratio.
#pragma once

#include <array>
#include <cstdint>

#include "codec/parol6_frames.hpp"

namespace robotd::parol6 {

inline constexpr double kMicrostepsPerMotorRevolution = 6400.0;

struct JointUnits {
  double gear_ratio;
  double min_rad;  // host-side limits (the firmware checks none), spec §10.2
  double max_rad;
  std::int32_t standby_steps;        // the counter after homing, spec §10.3
  double max_speed_steps_s;          // the API's hardware maximum, spec §10.4
  double max_acceleration_steps_s2;  // the API's: 3 × max speed
  double jog_max_steps_s;            // the API's jog maximum (80 %)
};

const std::array<JointUnits, kJoints>& joint_units();

// The vendor API's arithmetic (joint_units.cpp says which function each one follows). Joints 0 … 5;
// results outside int32 saturate, NaN gives 0.
double steps_per_rad(int joint);
double steps_to_rad(int joint, double steps);
std::int32_t rad_to_steps(int joint, double rad);  // nearest microstep, ties to even (the API)
double steps_per_s_to_rad_per_s(int joint, double steps_per_s);
std::int32_t rad_per_s_to_steps_per_s(int joint, double rad_per_s);  // truncated toward zero (both hosts)

/// Firmware clamp on every stepper's speed.
inline constexpr double kFirmwareMaxSpeedStepsPerSecond = 50000.0;

}  // namespace robotd::parol6
