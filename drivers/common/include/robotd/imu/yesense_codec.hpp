// The Yesense (元生创新, YIS series) IMU serial output protocol: splitting the byte stream into
// frames, decoding a frame's data items into an ImuReading in SI units, and encoding (for the
// emulator and tests). Pure: no I/O, no allocation, no exceptions.
//
// Source: "Yesense 通讯协议说明文档" v1.3 (2019-05-15), §2.1 and the worked example of §3.2.1.
//   frame    = 0x59 0x53 ("YS") | TID u16 LE | LEN u8 | MESSAGE (LEN bytes) | CK1 | CK2
//   checksum = over TID … last MESSAGE byte: CK1 += byte; CK2 += CK1 (both 8-bit, wrapping)
//   MESSAGE  = items, each DATA ID u8 | LEN u8 | DATA (LEN bytes); numbers little-endian int32
//   0x01 temperature  int16 × 0.01 °C        0x10 acceleration  3 × 1e-6 m/s²
//   0x20 angular rate 3 × 1e-6 deg/s         0x40 Euler         pitch, roll, yaw × 1e-6 deg
//   0x41 quaternion   q0 (w), q1, q2, q3 (x, y, z) × 1e-6     0x51 sample timestamp u32 µs
// Other items (magnetometer 0x30/0x31, UTC 0x50, sync-out time 0x52, position 0x60, velocity
// 0x70, …) are skipped by their length.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "robotd/imu/imu_reading.hpp"

namespace robotd::imu::yesense {

inline constexpr std::uint8_t kHeader1 = 0x59;  // 'Y'
inline constexpr std::uint8_t kHeader2 = 0x53;  // 'S'
inline constexpr std::size_t kPrefixBytes = 5;  // header, TID, LEN
inline constexpr std::size_t kChecksumBytes = 2;
inline constexpr std::size_t kMaxPayload = 255;
inline constexpr std::size_t kMaxFrame = kPrefixBytes + kMaxPayload + kChecksumBytes;
inline constexpr std::uint16_t kMaxSequence = 60'000;  // the device counts TID 1 … 60000

namespace item {
inline constexpr std::uint8_t kTemperature = 0x01;
inline constexpr std::uint8_t kAcceleration = 0x10;
inline constexpr std::uint8_t kAngularVelocity = 0x20;
inline constexpr std::uint8_t kMagneticNormalized = 0x30;
inline constexpr std::uint8_t kMagneticRaw = 0x31;
inline constexpr std::uint8_t kEuler = 0x40;
inline constexpr std::uint8_t kQuaternion = 0x41;
inline constexpr std::uint8_t kUtc = 0x50;
inline constexpr std::uint8_t kSampleTimestamp = 0x51;
inline constexpr std::uint8_t kSyncTimestamp = 0x52;
}  // namespace item

/// {CK1, CK2} over `bytes` (a frame's TID … last MESSAGE byte).
std::array<std::uint8_t, 2> checksum(std::span<const std::uint8_t> bytes) noexcept;

/// A checked frame: its TID and its MESSAGE.
struct Frame {
  std::uint16_t sequence = 0;
  std::span<const std::uint8_t> payload;
};

/// Splits a byte stream into checked frames. Bytes before a header are skipped; a frame whose
/// checksum fails, or whose LEN exceeds the bound, is dropped and the search resumes right after
/// its header, so a real frame hidden inside a false one is still found. Fixed buffer, no
/// allocation.
class FrameSplitter {
 public:
  struct Counters {
    std::uint64_t frames = 0;           // checked frames handed out
    std::uint64_t checksum_errors = 0;  // complete frames whose CK1/CK2 did not match
    std::uint64_t oversize = 0;         // headers whose LEN exceeded the bound
    std::uint64_t bytes_discarded = 0;  // bytes skipped while searching for a header
  };

  /// `max_payload` bounds LEN (at most kMaxPayload): a smaller bound resyncs sooner after noise.
  explicit FrameSplitter(std::size_t max_payload = kMaxPayload) noexcept;

  /// Consumes bytes from the front of `input` until a frame is complete (true; `frame` views the
  /// splitter's buffer and stays valid until the next call) or `input` is used up (false).
  /// Call again with the rest of `input` until it returns false.
  bool next(std::span<const std::uint8_t>& input, Frame& frame) noexcept;
  /// Forgets a partial frame (after a reconnect); keeps the counters.
  void reset() noexcept;

  const Counters& counters() const noexcept { return counters_; }

 private:
  enum class Scan : std::uint8_t { kNeedMore, kFrame, kDiscard };
  Scan scan_front(std::size_t& length) noexcept;
  void drop_front(std::size_t count) noexcept;

  std::size_t max_payload_;
  std::array<std::uint8_t, kMaxFrame> buffer_{};
  std::size_t size_ = 0;
  std::size_t handed_out_ = 0;  // the frame returned last, dropped on the next call
  Counters counters_;
};

enum class DecodeStatus : std::uint8_t {
  kOk,
  kTruncatedItem,  // an item's LEN runs past the end of MESSAGE
  kBadItemLength,  // a known item with a length other than the protocol's
  kBadQuaternion,  // a quaternion far from unit length (|q| outside 0.5 … 1.5)
};

const char* to_string(DecodeStatus status) noexcept;

/// Decodes a frame's MESSAGE into `out` (reset first; sequence = `sequence`). SI units: deg →
/// rad, deg/s → rad/s; the quaternion reordered to x, y, z, w and normalised. On an error `out`
/// is unspecified.
DecodeStatus decode(std::uint16_t sequence, std::span<const std::uint8_t> payload, ImuReading& out) noexcept;

/// The MESSAGE for the fields `reading` marks present, in item order 0x01, 0x10, 0x20, 0x40,
/// 0x41, 0x51 (values rounded to the protocol's resolution, clamped to its range). Returns its
/// length, or 0 if `out` is too small or no field is marked present.
std::size_t encode_payload(const ImuReading& reading, std::span<std::uint8_t> out) noexcept;

/// A whole frame around `payload`. Returns its length, or 0 if `out` is too small or `payload`
/// longer than kMaxPayload.
std::size_t encode_frame(std::uint16_t sequence, std::span<const std::uint8_t> payload,
                         std::span<std::uint8_t> out) noexcept;

/// encode_frame(reading.sequence, encode_payload(reading)).
std::size_t encode(const ImuReading& reading, std::span<std::uint8_t> out) noexcept;

}  // namespace robotd::imu::yesense
