// The HighTorque wire primitives (hightorque_and_ros2.md §1.6.1 and its errata): little-endian
// fields, float → integer conversion at each width (truncation toward zero, saturation, "no
// value" sentinels), and CAN-FD frames and length rounding. Internal to the codec.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "hightorque_codec.hpp"

namespace robotd::hightorque::wire {

using Bytes = std::span<std::uint8_t>;
using ConstBytes = std::span<const std::uint8_t>;

inline constexpr std::uint16_t kUnset16 = 0x8000;
inline constexpr std::uint32_t kUnset32 = 0x80000000U;
inline constexpr std::size_t kMaxFdLength = 64;

inline void put_u16(Bytes bytes, std::size_t at, std::uint16_t value) noexcept {
  bytes[at] = static_cast<std::uint8_t>(value & 0xFFU);
  bytes[at + 1] = static_cast<std::uint8_t>(value >> 8);
}

inline void put_u32(Bytes bytes, std::size_t at, std::uint32_t value) noexcept {
  put_u16(bytes, at, static_cast<std::uint16_t>(value & 0xFFFFU));
  put_u16(bytes, at + 2, static_cast<std::uint16_t>(value >> 16));
}

inline std::uint16_t get_u16(ConstBytes bytes, std::size_t at) noexcept {
  return static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
}

inline std::uint32_t get_u32(ConstBytes bytes, std::size_t at) noexcept {
  return get_u16(bytes, at) | (std::uint32_t{get_u16(bytes, at + 2)} << 16);
}

/// `value` truncated toward zero (the vendor's C cast) and saturated at ±`limit`; NaN becomes
/// `nan_value`. `limit` stays below the type's lowest() so a finite value never reads as unset.
template <typename Int>
Int truncate(double value, Int limit = std::numeric_limits<Int>::max(),
             Int nan_value = std::numeric_limits<Int>::lowest()) noexcept {
  if (std::isnan(value)) return nan_value;
  if (value >= static_cast<double>(limit)) return limit;
  if (value <= -static_cast<double>(limit)) return static_cast<Int>(-limit);
  return static_cast<Int>(value);
}

constexpr std::size_t width_bytes(Width width) noexcept { return width == Width::kInt16 ? 2 : 4; }

/// Writes `value` (in wire counts: motor units × the width's scale) at `width`.
inline void put_counts(Bytes bytes, std::size_t at, Width width, double value) noexcept {
  switch (width) {
    case Width::kInt16:
      put_u16(bytes, at, static_cast<std::uint16_t>(truncate<std::int16_t>(value)));
      return;
    case Width::kInt32:
      put_u32(bytes, at, static_cast<std::uint32_t>(truncate<std::int32_t>(value)));
      return;
    case Width::kFloat:
      put_u32(bytes, at, std::bit_cast<std::uint32_t>(static_cast<float>(value)));
      return;
  }
}

/// Reads a field at `width` in wire counts as the vendor's reply parser does: every value is a
/// number, 0x8000 included (−32768; a saturated reading, not "no value").
inline double get_counts(ConstBytes bytes, std::size_t at, Width width) noexcept {
  switch (width) {
    case Width::kInt16:
      return static_cast<std::int16_t>(get_u16(bytes, at));
    case Width::kInt32:
      return static_cast<std::int32_t>(get_u32(bytes, at));
    case Width::kFloat:
      return std::bit_cast<float>(get_u32(bytes, at));
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// Reads a command's field: in a command the sentinel means "no value" and reads as NaN.
inline double get_command_counts(ConstBytes bytes, std::size_t at, Width width) noexcept {
  const bool unset = (width == Width::kInt16 && get_u16(bytes, at) == kUnset16) ||
                     (width == Width::kInt32 && get_u32(bytes, at) == kUnset32);
  return unset ? std::numeric_limits<double>::quiet_NaN() : get_counts(bytes, at, width);
}

/// The smallest valid CAN-FD length ≥ `length` (0–8, 12, 16, 20, 24, 32, 48, 64); 64 beyond.
constexpr std::size_t fd_length(std::size_t length) noexcept {
  constexpr std::array<std::size_t, 7> kSteps{12, 16, 20, 24, 32, 48, 64};
  if (length <= 8) return length;
  for (const std::size_t step : kSteps) {
    if (length <= step) return step;
  }
  return kMaxFdLength;
}

/// A command or reply frame on the HighTorque bus: CAN-FD, 29-bit id, bit-rate switch; `length`
/// is rounded up to a valid CAN-FD length (the padding stays 0).
inline transport::CanMessage fd_frame(std::uint32_t id, std::size_t length) noexcept {
  transport::CanMessage message;
  message.id = id;
  message.extended = true;
  message.fd = true;
  message.bitrate_switch = true;
  message.length = static_cast<std::uint8_t>(fd_length(length));
  return message;
}

/// A frame to one motor: its id in bits 6…0 only, so that a bad id never becomes a block code.
inline transport::CanMessage motor_frame(Width width, int motor, std::size_t length) noexcept {
  return fd_frame(command_id(width, static_cast<int>(static_cast<unsigned>(motor) & 0x7FU)), length);
}

/// The bytes of a received frame, never more than its buffer holds.
inline ConstBytes payload(const transport::CanMessage& message) noexcept {
  return {message.data.data(), std::min<std::size_t>(message.length, message.data.size())};
}

}  // namespace robotd::hightorque::wire
