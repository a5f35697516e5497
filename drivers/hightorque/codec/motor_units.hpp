// Conversion between robotd's units and the motor's (§1.6.1 scaling table, errata "board
// units"): rad ↔ revolutions, N·m ↔ the firmware's torque unit, N·m/rad ↔ the motor's gains, and
// the wire counts per motor unit at each width. Internal to the codec.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "hightorque_codec.hpp"

namespace robotd::hightorque::units {

inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

enum class Quantity : std::uint8_t { kPosition, kVelocity, kAcceleration, kTorque, kGain, kElectrical, kTemperature };

/// Wire counts per motor unit at `width` (the vendor's convert.c: pos 1e-4 / 1e-5 rev, vel
/// 2.5e-4 / 1e-5 rev/s, acc 1e-3 / 1e-5 rev/s², τ 0.01 / 0.001, gains, volts, amps and °C
/// 0.1 / 0.001; float as is).
constexpr double counts_per_unit(Quantity quantity, Width width) noexcept {
  if (width == Width::kFloat) return 1.0;
  const bool narrow = width == Width::kInt16;
  switch (quantity) {
    case Quantity::kPosition:
      return narrow ? 1e4 : 1e5;
    case Quantity::kVelocity:
      return narrow ? 4e3 : 1e5;
    case Quantity::kAcceleration:
      return narrow ? 1e3 : 1e5;
    case Quantity::kTorque:
      return narrow ? 1e2 : 1e3;
    case Quantity::kGain:
    case Quantity::kElectrical:
    case Quantity::kTemperature:
      return narrow ? 1e1 : 1e3;
  }
  return 1.0;
}

/// The vendors' 2π, a float literal in both SDKs (convert.c MY_2PI, motor.h my_2pi).
inline constexpr float kTwoPiF = 6.28318530717F;

/// robotd's unit → the motor's, in float like the vendor's code: its functions take float, turn
/// radians into revolutions by a float division by its 2π and multiply gains by it in float.
inline float to_motor(Quantity quantity, double value, const MotorScaling& scaling) noexcept {
  const auto given = static_cast<float>(value);
  switch (quantity) {
    case Quantity::kPosition:
    case Quantity::kVelocity:
    case Quantity::kAcceleration:
      return given / kTwoPiF;
    case Quantity::kTorque:
      return static_cast<float>((static_cast<double>(given) - scaling.torque_offset_nm) / scaling.torque_per_unit);
    case Quantity::kGain:
      return given * kTwoPiF / static_cast<float>(scaling.gain_factor);
    case Quantity::kElectrical:
    case Quantity::kTemperature:
      return given;
  }
  return given;
}

/// The motor's unit → robotd's (float arithmetic, as the vendor's parser).
inline double from_motor(Quantity quantity, float value, const MotorScaling& scaling) noexcept {
  switch (quantity) {
    case Quantity::kPosition:
    case Quantity::kVelocity:
    case Quantity::kAcceleration:
      return value * kTwoPiF;
    case Quantity::kTorque:
      return static_cast<float>(value * scaling.torque_per_unit + scaling.torque_offset_nm);
    case Quantity::kGain:
      return value * static_cast<float>(scaling.gain_factor) / kTwoPiF;
    case Quantity::kElectrical:
    case Quantity::kTemperature:
      return value;
  }
  return value;
}

/// A value in robotd's units as wire counts at `width` before truncation: the float product of
/// the motor's value and the width's scale (convert.c data_float2int).
inline float to_counts(Quantity quantity, double value, Width width, const MotorScaling& scaling) noexcept {
  return to_motor(quantity, value, scaling) * static_cast<float>(counts_per_unit(quantity, width));
}

/// Wire counts at `width` back into robotd's units: the counts as a float divided by the width's
/// scale in float (convert.c data_int2float); NaN stays NaN.
inline double from_counts(Quantity quantity, double counts, Width width, const MotorScaling& scaling) noexcept {
  return from_motor(quantity, static_cast<float>(counts) / static_cast<float>(counts_per_unit(quantity, width)),
                    scaling);
}

}  // namespace robotd::hightorque::units
