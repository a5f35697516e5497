#include "recording/little_endian.hpp"

#include <bit>
#include <limits>

namespace robotctl::recording {
namespace {

constexpr std::size_t kLargestArray = std::numeric_limits<std::uint16_t>::max();

}  // namespace

void LittleEndianWriter::unsigned_bytes(std::uint64_t value, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) out_ += static_cast<char>((value >> (8 * i)) & 0xFFU);
}

void LittleEndianWriter::u8(std::uint8_t value) { unsigned_bytes(value, 1); }
void LittleEndianWriter::u16(std::uint16_t value) { unsigned_bytes(value, 2); }
void LittleEndianWriter::u32(std::uint32_t value) { unsigned_bytes(value, 4); }
void LittleEndianWriter::i64(std::int64_t value) { unsigned_bytes(static_cast<std::uint64_t>(value), 8); }
void LittleEndianWriter::f64(double value) { unsigned_bytes(std::bit_cast<std::uint64_t>(value), 8); }

bool LittleEndianWriter::i32_array(const std::vector<std::int32_t>& values) {
  if (values.size() > kLargestArray) return false;
  u16(static_cast<std::uint16_t>(values.size()));
  for (const std::int32_t value : values) unsigned_bytes(static_cast<std::uint32_t>(value), 4);
  return true;
}

bool LittleEndianWriter::f32_array(const std::vector<float>& values) {
  if (values.size() > kLargestArray) return false;
  u16(static_cast<std::uint16_t>(values.size()));
  for (const float value : values) unsigned_bytes(std::bit_cast<std::uint32_t>(value), 4);
  return true;
}

bool LittleEndianWriter::f64_array(const std::vector<double>& values) {
  if (values.size() > kLargestArray) return false;
  u16(static_cast<std::uint16_t>(values.size()));
  for (const double value : values) f64(value);
  return true;
}

std::uint64_t LittleEndianReader::unsigned_bytes(std::size_t count) {
  if (failed_ || data_.size() < count) {
    failed_ = true;
    return 0;
  }
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < count; ++i) {
    value |= static_cast<std::uint64_t>(static_cast<unsigned char>(data_[i])) << (8 * i);
  }
  data_.remove_prefix(count);
  return value;
}

double LittleEndianReader::f64() { return std::bit_cast<double>(unsigned_bytes(8)); }

std::string_view LittleEndianReader::bytes(std::size_t count) {
  if (failed_ || data_.size() < count) {
    failed_ = true;
    return {};
  }
  const std::string_view taken = data_.substr(0, count);
  data_.remove_prefix(count);
  return taken;
}

std::vector<std::int32_t> LittleEndianReader::i32_array() {
  std::vector<std::int32_t> values(u16());
  for (auto& value : values) value = static_cast<std::int32_t>(static_cast<std::uint32_t>(unsigned_bytes(4)));
  return values;
}

std::vector<float> LittleEndianReader::f32_array() {
  std::vector<float> values(u16());
  for (auto& value : values) value = std::bit_cast<float>(static_cast<std::uint32_t>(unsigned_bytes(4)));
  return values;
}

std::vector<double> LittleEndianReader::f64_array() {
  std::vector<double> values(u16());
  for (auto& value : values) value = f64();
  return values;
}

}  // namespace robotctl::recording
