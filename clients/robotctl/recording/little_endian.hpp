// Fixed-width little-endian values appended to, and read back from, a byte string: the
// encoding of every number in a robotd recording (docs/recording.md). Whatever the host's byte
// order, the bytes are the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace robotctl::recording {

class LittleEndianWriter {
 public:
  explicit LittleEndianWriter(std::string& out) : out_(out) {}

  void u8(std::uint8_t value);
  void u16(std::uint16_t value);
  void u32(std::uint32_t value);
  void i64(std::int64_t value);
  void f64(double value);
  void bytes(std::string_view data) { out_ += data; }
  /// A u16 count, then the values. Fails (returns false, writes nothing) above 65535 values.
  bool i32_array(const std::vector<std::int32_t>& values);
  bool f32_array(const std::vector<float>& values);
  bool f64_array(const std::vector<double>& values);

 private:
  void unsigned_bytes(std::uint64_t value, std::size_t count);
  std::string& out_;
};

/// Reads values in order. A read past the end sets failed() and returns zeros; check failed()
/// once at the end.
class LittleEndianReader {
 public:
  explicit LittleEndianReader(std::string_view data) : data_(data) {}

  std::uint8_t u8() { return static_cast<std::uint8_t>(unsigned_bytes(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(unsigned_bytes(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(unsigned_bytes(4)); }
  std::int64_t i64() { return static_cast<std::int64_t>(unsigned_bytes(8)); }
  double f64();
  std::string_view bytes(std::size_t count);
  std::vector<std::int32_t> i32_array();
  std::vector<float> f32_array();
  std::vector<double> f64_array();

  bool failed() const { return failed_; }
  /// Every byte read, and none past the end.
  bool consumed_exactly() const { return !failed_ && data_.empty(); }

 private:
  std::uint64_t unsigned_bytes(std::size_t count);
  std::string_view data_;
  bool failed_ = false;
};

}  // namespace robotctl::recording
