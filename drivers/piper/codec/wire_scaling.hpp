// The PiPER wire format's primitives (piper_can.md §1, §3, §4.7): big-endian fields in a CAN
// payload, SI values rounded and saturated into integer fields, and the MIT quantisation.
// Internal to the codec.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>

#include "robotd/transport/can_message.hpp"

namespace robotd::piper::wire {

using Payload = decltype(transport::CanMessage::data);

inline constexpr double kMilliDegPerRad = 1000.0 * 180.0 / std::numbers::pi;  // 0.001° counts
inline constexpr double kDeciDegPerRad = 10.0 * 180.0 / std::numbers::pi;     // 0.1° counts
inline constexpr double kMicrometresPerMetre = 1e6;

/// `value` rounded to the nearest integer and saturated to [lowest, highest] (never wrapped);
/// NaN becomes 0.
template <typename Int>
Int saturate(double value, Int lowest = std::numeric_limits<Int>::lowest(),
             Int highest = std::numeric_limits<Int>::max()) noexcept {
  if (std::isnan(value)) return 0;
  if (value <= static_cast<double>(lowest)) return lowest;
  if (value >= static_cast<double>(highest)) return highest;
  return static_cast<Int>(std::lround(value));
}

inline void put_u16(Payload& data, std::size_t at, std::uint16_t value) noexcept {
  data[at] = static_cast<std::uint8_t>(value >> 8);
  data[at + 1] = static_cast<std::uint8_t>(value);
}

inline void put_i16(Payload& data, std::size_t at, std::int16_t value) noexcept {
  put_u16(data, at, static_cast<std::uint16_t>(value));
}

inline void put_i32(Payload& data, std::size_t at, std::int32_t value) noexcept {
  const auto bits = static_cast<std::uint32_t>(value);
  put_u16(data, at, static_cast<std::uint16_t>(bits >> 16));
  put_u16(data, at + 2, static_cast<std::uint16_t>(bits));
}

inline std::uint16_t get_u16(const Payload& data, std::size_t at) noexcept {
  return static_cast<std::uint16_t>((data[at] << 8) | data[at + 1]);
}

inline std::int16_t get_i16(const Payload& data, std::size_t at) noexcept {
  return static_cast<std::int16_t>(get_u16(data, at));
}

inline std::int32_t get_i32(const Payload& data, std::size_t at) noexcept {
  return static_cast<std::int32_t>((std::uint32_t{get_u16(data, at)} << 16) | get_u16(data, at + 2));
}

/// One quantised MIT field: `bits` wide over [min, max].
struct MitRange {
  double min;
  double max;
  int bits;
};

/// The SDK's FloatToUint after clamping into the range (the SDK does not clamp): truncation
/// toward zero of (x − min)·(2^bits − 1)/(max − min). NaN encodes as 0.0 would.
inline std::uint32_t mit_quantise(double value, MitRange range) noexcept {
  const double full_scale = static_cast<double>((1U << range.bits) - 1);
  if (std::isnan(value)) value = 0.0;
  if (value < range.min) value = range.min;
  if (value > range.max) value = range.max;
  const double scaled = (value - range.min) * full_scale / (range.max - range.min);
  return scaled >= full_scale ? static_cast<std::uint32_t>(full_scale) : static_cast<std::uint32_t>(scaled);
}

/// The inverse (the SDK's UintToFloat).
inline double mit_value(std::uint32_t quantised, MitRange range) noexcept {
  const double full_scale = static_cast<double>((1U << range.bits) - 1);
  return static_cast<double>(quantised) * (range.max - range.min) / full_scale + range.min;
}

}  // namespace robotd::piper::wire
