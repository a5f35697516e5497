// The Yesense serial output protocol of yesense_codec.hpp. Nothing here allocates.
#include "robotd/imu/yesense_codec.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include "robotd/kinematics/rotation.hpp"

namespace robotd::imu::yesense {
namespace {

constexpr std::size_t kLengthOffset = 4;
constexpr std::size_t kItemHeaderBytes = 2;  // DATA ID, LEN
constexpr double kMicro = 1e-6;              // acceleration, rates, angles, quaternion
constexpr double kCenti = 0.01;              // temperature
constexpr double kRadPerDeg = std::numbers::pi / 180.0;

constexpr std::size_t kTemperatureBytes = 2;
constexpr std::size_t kVectorBytes = 12;
constexpr std::size_t kQuaternionBytes = 16;
constexpr std::size_t kTimestampBytes = 4;

/// The protocol's length for the items decode() reads (0: skipped whatever its length).
std::size_t expected_length(std::uint8_t id) noexcept {
  switch (id) {
    case item::kTemperature:
      return kTemperatureBytes;
    case item::kAcceleration:
    case item::kAngularVelocity:
    case item::kEuler:
      return kVectorBytes;
    case item::kQuaternion:
      return kQuaternionBytes;
    case item::kSampleTimestamp:
      return kTimestampBytes;
    default:
      return 0;
  }
}

std::uint32_t load_u32(const std::uint8_t* bytes) noexcept {
  return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8U) |
         (static_cast<std::uint32_t>(bytes[2]) << 16U) | (static_cast<std::uint32_t>(bytes[3]) << 24U);
}

std::int32_t load_i32(const std::uint8_t* bytes) noexcept { return static_cast<std::int32_t>(load_u32(bytes)); }

/// `count` little-endian int32 values × `scale`.
template <std::size_t N>
std::array<double, N> load_scaled(const std::uint8_t* bytes, double scale) noexcept {
  std::array<double, N> values{};
  for (std::size_t i = 0; i < N; ++i) values[i] = load_i32(bytes + 4 * i) * scale;
  return values;
}

/// Writes bytes at the end of a fixed span; remembers when it ran out of room.
class Writer {
 public:
  explicit Writer(std::span<std::uint8_t> out) noexcept : out_(out) {}

  void byte(std::uint8_t value) noexcept {
    if (size_ < out_.size()) {
      out_[size_] = value;
    } else {
      overflow_ = true;
    }
    ++size_;
  }
  void u32(std::uint32_t value) noexcept {
    for (unsigned shift = 0; shift < 32; shift += 8) byte(static_cast<std::uint8_t>(value >> shift));
  }
  /// value / scale rounded, clamped to the int32 range.
  void scaled(double value, double scale) noexcept {
    constexpr double kMin = std::numeric_limits<std::int32_t>::min();
    constexpr double kMax = std::numeric_limits<std::int32_t>::max();
    const double raw = std::isfinite(value) ? std::clamp(std::round(value / scale), kMin, kMax) : 0.0;
    u32(static_cast<std::uint32_t>(static_cast<std::int32_t>(raw)));
  }
  void item(std::uint8_t id, std::size_t length) noexcept {
    byte(id);
    byte(static_cast<std::uint8_t>(length));
  }

  std::size_t size() const noexcept { return overflow_ ? 0 : size_; }

 private:
  std::span<std::uint8_t> out_;
  std::size_t size_ = 0;
  bool overflow_ = false;
};

}  // namespace

std::array<std::uint8_t, 2> checksum(std::span<const std::uint8_t> bytes) noexcept {
  std::uint8_t ck1 = 0;
  std::uint8_t ck2 = 0;
  for (const std::uint8_t byte : bytes) {
    ck1 = static_cast<std::uint8_t>(ck1 + byte);
    ck2 = static_cast<std::uint8_t>(ck2 + ck1);
  }
  return {ck1, ck2};
}

// --- splitting ------------------------------------------------------------------------------------

FrameSplitter::FrameSplitter(std::size_t max_payload) noexcept : max_payload_(std::min(max_payload, kMaxPayload)) {}

void FrameSplitter::reset() noexcept {
  size_ = 0;
  handed_out_ = 0;
}

void FrameSplitter::drop_front(std::size_t count) noexcept {
  count = std::min(count, size_);
  std::memmove(buffer_.data(), buffer_.data() + count, size_ - count);
  size_ -= count;
}

FrameSplitter::Scan FrameSplitter::scan_front(std::size_t& length) noexcept {
  if (size_ == 0) return Scan::kNeedMore;
  if (buffer_[0] != kHeader1) {
    const auto* found = std::find(buffer_.data() + 1, buffer_.data() + size_, kHeader1);
    length = static_cast<std::size_t>(found - buffer_.data());
    counters_.bytes_discarded += length;
    return Scan::kDiscard;
  }
  if (size_ < 2) return Scan::kNeedMore;
  if (buffer_[1] != kHeader2) {
    length = 1;
    ++counters_.bytes_discarded;
    return Scan::kDiscard;
  }
  if (size_ < kPrefixBytes) return Scan::kNeedMore;
  const std::size_t payload = buffer_[kLengthOffset];
  if (payload > max_payload_) {
    length = 2;  // past this header: the next one may start inside what it claimed
    ++counters_.oversize;
    counters_.bytes_discarded += length;
    return Scan::kDiscard;
  }
  const std::size_t total = kPrefixBytes + payload + kChecksumBytes;
  if (size_ < total) return Scan::kNeedMore;
  const auto sum = checksum(std::span<const std::uint8_t>(buffer_.data() + 2, payload + 3));
  if (sum[0] != buffer_[total - 2] || sum[1] != buffer_[total - 1]) {
    length = 2;
    ++counters_.checksum_errors;
    counters_.bytes_discarded += length;
    return Scan::kDiscard;
  }
  length = total;
  return Scan::kFrame;
}

bool FrameSplitter::next(std::span<const std::uint8_t>& input, Frame& frame) noexcept {
  drop_front(handed_out_);
  handed_out_ = 0;
  for (;;) {
    std::size_t length = 0;
    switch (scan_front(length)) {
      case Scan::kFrame:
        handed_out_ = length;
        ++counters_.frames;
        frame.sequence = static_cast<std::uint16_t>(buffer_[2] | (buffer_[3] << 8U));
        frame.payload = std::span<const std::uint8_t>(buffer_.data() + kPrefixBytes, length - kPrefixBytes - 2);
        return true;
      case Scan::kDiscard:
        drop_front(length);
        break;
      case Scan::kNeedMore: {
        if (input.empty()) return false;
        const std::size_t count = std::min(input.size(), buffer_.size() - size_);
        std::memcpy(buffer_.data() + size_, input.data(), count);
        size_ += count;
        input = input.subspan(count);
        break;
      }
    }
  }
}

// --- decoding -------------------------------------------------------------------------------------

const char* to_string(DecodeStatus status) noexcept {
  switch (status) {
    case DecodeStatus::kOk:
      return "ok";
    case DecodeStatus::kTruncatedItem:
      return "a data item runs past the end of the message";
    case DecodeStatus::kBadItemLength:
      return "a data item has the wrong length for its id";
    case DecodeStatus::kBadQuaternion:
      return "the quaternion is far from unit length";
  }
  return "unknown";
}

DecodeStatus decode(std::uint16_t sequence, std::span<const std::uint8_t> payload, ImuReading& out) noexcept {
  out = ImuReading{};
  out.sequence = sequence;
  std::size_t offset = 0;
  while (offset < payload.size()) {
    if (payload.size() - offset < kItemHeaderBytes) return DecodeStatus::kTruncatedItem;
    const std::uint8_t id = payload[offset];
    const std::size_t length = payload[offset + 1];
    const std::uint8_t* data = payload.data() + offset + kItemHeaderBytes;
    offset += kItemHeaderBytes + length;
    if (offset > payload.size()) return DecodeStatus::kTruncatedItem;
    const std::size_t expected = expected_length(id);
    if (expected == 0) continue;  // an item this decoder does not read
    if (length != expected) return DecodeStatus::kBadItemLength;
    switch (id) {
      case item::kTemperature:
        out.temperature_c = static_cast<std::int16_t>(data[0] | (data[1] << 8U)) * kCenti;
        out.has_temperature = true;
        break;
      case item::kAcceleration:
        out.linear_acceleration_m_s2 = load_scaled<3>(data, kMicro);
        out.has_linear_acceleration = true;
        break;
      case item::kAngularVelocity:
        out.angular_velocity_rad_s = load_scaled<3>(data, kMicro * kRadPerDeg);
        out.has_angular_velocity = true;
        break;
      case item::kEuler: {
        const auto pitch_roll_yaw = load_scaled<3>(data, kMicro * kRadPerDeg);
        out.euler_rad = EulerRad{.roll = pitch_roll_yaw[1], .pitch = pitch_roll_yaw[0], .yaw = pitch_roll_yaw[2]};
        out.has_euler = true;
        break;
      }
      case item::kQuaternion: {
        const auto wxyz = load_scaled<4>(data, kMicro);
        const double norm = std::sqrt(wxyz[0] * wxyz[0] + wxyz[1] * wxyz[1] + wxyz[2] * wxyz[2] + wxyz[3] * wxyz[3]);
        if (norm < 0.5 || norm > 1.5) return DecodeStatus::kBadQuaternion;
        out.orientation_xyzw = {wxyz[1] / norm, wxyz[2] / norm, wxyz[3] / norm, wxyz[0] / norm};
        out.has_orientation = true;
        break;
      }
      case item::kSampleTimestamp:
        out.sample_time_us = load_u32(data);
        out.has_sample_time = true;
        break;
      default:
        break;
    }
  }
  if (!out.has_orientation && out.has_euler) {  // a device set to send Euler angles only
    out.orientation_xyzw =
        kinematics::quaternion_xyzw_from_rpy({out.euler_rad.roll, out.euler_rad.pitch, out.euler_rad.yaw});
    out.has_orientation = true;
  }
  return DecodeStatus::kOk;
}

// --- encoding -------------------------------------------------------------------------------------

std::size_t encode_payload(const ImuReading& reading, std::span<std::uint8_t> out) noexcept {
  Writer writer(out);
  if (reading.has_temperature) {
    const double raw = std::isfinite(reading.temperature_c) ? std::round(reading.temperature_c / kCenti) : 0.0;
    const auto value = static_cast<std::int16_t>(std::clamp(raw, -32768.0, 32767.0));
    writer.item(item::kTemperature, kTemperatureBytes);
    writer.byte(static_cast<std::uint8_t>(static_cast<std::uint16_t>(value) & 0xFFU));
    writer.byte(static_cast<std::uint8_t>(static_cast<std::uint16_t>(value) >> 8U));
  }
  if (reading.has_linear_acceleration) {
    writer.item(item::kAcceleration, kVectorBytes);
    for (const double value : reading.linear_acceleration_m_s2) writer.scaled(value, kMicro);
  }
  if (reading.has_angular_velocity) {
    writer.item(item::kAngularVelocity, kVectorBytes);
    for (const double value : reading.angular_velocity_rad_s) writer.scaled(value, kMicro * kRadPerDeg);
  }
  if (reading.has_euler) {
    writer.item(item::kEuler, kVectorBytes);
    writer.scaled(reading.euler_rad.pitch, kMicro * kRadPerDeg);
    writer.scaled(reading.euler_rad.roll, kMicro * kRadPerDeg);
    writer.scaled(reading.euler_rad.yaw, kMicro * kRadPerDeg);
  }
  if (reading.has_orientation) {
    const auto& q = reading.orientation_xyzw;
    writer.item(item::kQuaternion, kQuaternionBytes);
    for (const double value : {q[3], q[0], q[1], q[2]}) writer.scaled(value, kMicro);
  }
  if (reading.has_sample_time) {
    writer.item(item::kSampleTimestamp, kTimestampBytes);
    writer.u32(reading.sample_time_us);
  }
  return writer.size();
}

std::size_t encode_frame(std::uint16_t sequence, std::span<const std::uint8_t> payload,
                         std::span<std::uint8_t> out) noexcept {
  const std::size_t total = kPrefixBytes + payload.size() + kChecksumBytes;
  if (payload.size() > kMaxPayload || out.size() < total) return 0;
  out[0] = kHeader1;
  out[1] = kHeader2;
  out[2] = static_cast<std::uint8_t>(sequence & 0xFFU);
  out[3] = static_cast<std::uint8_t>(sequence >> 8U);
  out[kLengthOffset] = static_cast<std::uint8_t>(payload.size());
  std::copy(payload.begin(), payload.end(), out.begin() + kPrefixBytes);
  const auto sum = checksum(out.subspan(2, payload.size() + 3));
  out[total - 2] = sum[0];
  out[total - 1] = sum[1];
  return total;
}

std::size_t encode(const ImuReading& reading, std::span<std::uint8_t> out) noexcept {
  std::array<std::uint8_t, kMaxPayload> payload{};
  const std::size_t length = encode_payload(reading, payload);
  if (length == 0) return 0;
  return encode_frame(reading.sequence, std::span<const std::uint8_t>(payload.data(), length), out);
}

}  // namespace robotd::imu::yesense
