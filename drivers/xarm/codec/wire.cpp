// The wire's primitive values (§2.4): big-endian integers, little-endian IEEE-754 singles.
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>

#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

/// Rounds to the nearest float. A finite value beyond float's range saturates at ±FLT_MAX
/// instead of becoming ±inf, which newer firmware reads as "keep the current value" (§4.1).
float to_float(double value) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (std::isfinite(value) && std::abs(value) > kMax) return static_cast<float>(value < 0 ? -kMax : kMax);
  return static_cast<float>(value);
}

}  // namespace

ByteWriter& ByteWriter::u8(std::uint8_t value) {
  bytes_.push_back(value);
  return *this;
}

ByteWriter& ByteWriter::u16_be(std::uint16_t value) {
  u8(static_cast<std::uint8_t>(value >> 8));
  return u8(static_cast<std::uint8_t>(value));
}

ByteWriter& ByteWriter::u32_be(std::uint32_t value) {
  u16_be(static_cast<std::uint16_t>(value >> 16));
  return u16_be(static_cast<std::uint16_t>(value));
}

ByteWriter& ByteWriter::u64_be(std::uint64_t value) {
  u32_be(static_cast<std::uint32_t>(value >> 32));
  return u32_be(static_cast<std::uint32_t>(value));
}

ByteWriter& ByteWriter::f32_le(double value) {
  const auto bits = std::bit_cast<std::uint32_t>(to_float(value));
  for (int shift = 0; shift < 32; shift += 8) u8(static_cast<std::uint8_t>(bits >> shift));
  return *this;
}

ByteWriter& ByteWriter::bytes(ByteView data) {
  bytes_.insert(bytes_.end(), data.begin(), data.end());
  return *this;
}

std::optional<std::uint8_t> ByteReader::u8() {
  if (remaining() < 1) return std::nullopt;
  return data_[offset_++];
}

std::optional<std::uint16_t> ByteReader::u16_be() {
  if (remaining() < 2) return std::nullopt;
  const auto value = static_cast<std::uint16_t>((data_[offset_] << 8) | data_[offset_ + 1]);
  offset_ += 2;
  return value;
}

std::optional<std::uint32_t> ByteReader::u32_be() {
  if (remaining() < 4) return std::nullopt;
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) value = (value << 8) | data_[offset_ + i];
  offset_ += 4;
  return value;
}

std::optional<std::uint64_t> ByteReader::u64_be() {
  if (remaining() < 8) return std::nullopt;
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < 8; ++i) value = (value << 8) | data_[offset_ + i];
  offset_ += 8;
  return value;
}

std::optional<double> ByteReader::f32_le() {
  if (remaining() < 4) return std::nullopt;
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < 4; ++i) bits |= static_cast<std::uint32_t>(data_[offset_ + i]) << (8 * i);
  offset_ += 4;
  return static_cast<double>(std::bit_cast<float>(bits));
}

}  // namespace robotd::xarm
