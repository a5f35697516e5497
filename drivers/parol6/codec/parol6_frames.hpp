// The PAROL6 control board's serial protocol (../shared/protocols/parol6_serial.md) as plain
// values: the host's 56-byte command frame, the board's 60-byte reply, the stream parser that
// finds frames in a byte stream, and the joint unit conversions (microsteps ↔ rad).
//
// Frames carry vendor units (microsteps, microsteps/s, 0..255 gripper set points); conversion
// to SI happens in the driver through joint_units.hpp, never inside robotd's surface.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace robotd::parol6 {

inline constexpr int kJoints = 6;
inline constexpr std::size_t kHostFrameSize = 56;   // 3 start + LEN + 52
inline constexpr std::size_t kRobotFrameSize = 60;  // 3 start + LEN + 56
inline constexpr std::uint8_t kHostLength = 52;
inline constexpr std::uint8_t kRobotLength = 56;
inline constexpr std::uint8_t kHostCrcPlaceholder = 228;   // 0xE4, what CMD and the API send
inline constexpr std::uint8_t kRobotCrcPlaceholder = 212;  // 0xD4, what the board sends

/// Command byte (body offset 36). Decimal values on the wire, despite the docs' "0x" labels.
namespace command {
inline constexpr std::uint8_t kNone = 0;  // power-up value: no action
inline constexpr std::uint8_t kDemo = 69;
inline constexpr std::uint8_t kHome = 100;
inline constexpr std::uint8_t kEnable = 101;
inline constexpr std::uint8_t kDisable = 102;
inline constexpr std::uint8_t kClearError = 103;
inline constexpr std::uint8_t kJog = 123;           // speed mode, no ramp
inline constexpr std::uint8_t kGoToPosition = 156;  // position + speed feed-forward
inline constexpr std::uint8_t kIdle = 255;          // dummy: no motion, homing continues
}  // namespace command

/// Gripper command byte (body offset 46), MSB-first bitfield.
namespace gripper_command {
inline constexpr std::uint8_t kActivate = 0x80;
inline constexpr std::uint8_t kMove = 0x40;
inline constexpr std::uint8_t kEstop = 0x20;
inline constexpr std::uint8_t kReleaseDirection = 0x10;
}  // namespace gripper_command

enum class GripperMode : std::uint8_t { kOperate = 0, kCalibrate = 1, kClearError = 2 };

/// Gripper status byte as the SSG-48 firmware packs it (Spectral-Micro-BLDC-controller,
/// Gripper_pack_data: MSB first) and the control board forwards it unchanged as reply byte 51.
/// The PAROL6 API reads the object code from 0x08/0x04 instead, where the errors are.
namespace gripper_status {
inline constexpr std::uint8_t kActivated = 0x80;
inline constexpr std::uint8_t kMoving = 0x40;
inline constexpr std::uint8_t kObjectBit0 = 0x20;
inline constexpr std::uint8_t kObjectBit1 = 0x10;
inline constexpr std::uint8_t kTemperatureError = 0x08;
inline constexpr std::uint8_t kTimeoutError = 0x04;
inline constexpr std::uint8_t kEstopError = 0x02;
inline constexpr std::uint8_t kCalibrated = 0x01;
}  // namespace gripper_status

enum class ObjectDetection : std::uint8_t {
  kMoving = 0,
  kClosingOnObject = 1,
  kOpeningOnObject = 2,
  kAtPosition = 3,
};
/// code = bit 0x20 | bit 0x10 << 1 (the gripper firmware's packing; the reply's separate
/// object-detection byte 52 is a constant 1 on the board firmware).
ObjectDetection object_detection(std::uint8_t gripper_status_byte);

/// I/O bitfield bits (reply body offset 37; host body offset 38 uses OUT1/OUT2 only).
namespace io {
inline constexpr std::uint8_t kIn1 = 0x80;
inline constexpr std::uint8_t kIn2 = 0x40;
inline constexpr std::uint8_t kOut1 = 0x20;
inline constexpr std::uint8_t kOut2 = 0x10;
inline constexpr std::uint8_t kEstopReleased = 0x08;  // 1 = released (NC contact closed), 0 = pressed
}  // namespace io

/// PC → robot (spec §4). Field order as on the wire.
struct HostFrame {
  std::array<std::int32_t, kJoints> position_steps{};  // int24
  std::array<std::int32_t, kJoints> speed_steps_s{};   // int24
  std::uint8_t command = command::kIdle;
  std::uint8_t affected_joints = 0xFF;  // stored, never used by the firmware
  std::uint8_t io = 0;                  // only io::kOut1 / io::kOut2 matter
  std::uint8_t timeout_ms = 0;          // stored, never used by the firmware
  std::int16_t gripper_position = 0;    // 0 open … 255 closed
  std::int16_t gripper_speed = 0;       // 0 … 255
  std::int16_t gripper_current_ma = 0;  // 0 … 1300 mA
  std::uint8_t gripper_command = 0;     // gripper_command bits
  std::uint8_t gripper_mode = 0;        // GripperMode, one frame only for 1 and 2
  std::uint8_t gripper_id = 0;          // CAN node id 0 … 15
  std::uint8_t crc = kHostCrcPlaceholder;
};

/// Robot → PC (spec §5).
struct RobotFrame {
  std::array<std::int32_t, kJoints> position_steps{};
  std::array<std::int32_t, kJoints> speed_steps_s{};
  std::uint8_t homed = 0x03;  // bit (7 − j) = joint j homed; bits 0, 1 always 1
  std::uint8_t io = 0x0F;     // io bits; bits 0–2 always 1
  std::uint8_t temperature_error = 0x03;
  std::uint8_t position_error = 0x03;
  std::uint16_t timing_ticks = 0;    // ticks of 128/90 MHz between the last two valid frames
  std::uint8_t timeout_error = 100;  // constant on this firmware
  std::uint8_t echoed_command = 0;
  std::uint8_t gripper_id = 0;
  std::int16_t gripper_position = 0;
  std::int16_t gripper_speed = 1;
  std::int16_t gripper_current = 2;
  std::uint8_t gripper_status = 1;
  std::uint8_t object_detection = 1;
  std::uint8_t crc = kRobotCrcPlaceholder;

  bool joint_homed(int joint) const;  // joint 0 … 5
  bool all_homed() const;
  bool estop_pressed() const { return (io & io::kEstopReleased) == 0; }
};

inline constexpr double kTimingTickSeconds = 128.0 / 90e6;  // 1.4222 µs

// --- primitives (spec §3) ----------------------------------------------------------------------

/// The range of the int24 fields (positions and speeds in steps).
inline constexpr std::int32_t kMinInt24 = -8'388'608;
inline constexpr std::int32_t kMaxInt24 = 8'388'607;

/// value modulo 2^24, big-endian; values outside ±2^23 wrap like the firmware's.
void put_int24(std::span<std::uint8_t, 3> out, std::int32_t value);
std::int32_t get_int24(std::span<const std::uint8_t, 3> in);
/// Element 0 is the MSB.
std::uint8_t pack_bits(const std::array<bool, 8>& bits);
std::array<bool, 8> unpack_bits(std::uint8_t byte);

// --- frames ------------------------------------------------------------------------------------

std::array<std::uint8_t, kHostFrameSize> encode(const HostFrame& frame);
std::array<std::uint8_t, kRobotFrameSize> encode(const RobotFrame& frame);

/// The fields of an accepted body (the bytes after LEN, end bytes included), read at the
/// firmware's fixed offsets whatever LEN said: nullopt if the body is too short to hold them
/// (host: 50 bytes before the end bytes; robot: 54).
std::optional<HostFrame> decode_host_body(std::span<const std::uint8_t> body);
std::optional<RobotFrame> decode_robot_body(std::span<const std::uint8_t> body);

/// Finds frames in a byte stream (spec §2.1). No allocation: a fixed buffer.
///   kFirmware: as the board parses: after FF FF FF the next byte is LEN whatever its value;
///              LEN bytes are collected; the frame is accepted if its last two are 01 02, and
///              either way the parser hunts again from the next byte.
///   kResync:   as the API's host parser: on bad end bytes it advances one byte past the start
///              of the rejected candidate and rescans, so one lost or garbled byte costs one
///              frame, not the link.
class FrameParser {
 public:
  enum class Style : std::uint8_t { kFirmware, kResync };
  static constexpr std::size_t kBufferSize = 1024;

  explicit FrameParser(Style style) : style_(style) {}

  /// Feeds bytes; calls on_body(std::span<const std::uint8_t> body) for each accepted frame.
  template <class OnBody>
  void feed(std::span<const std::uint8_t> bytes, OnBody&& on_body);

  std::uint64_t frames() const { return frames_; }
  std::uint64_t rejected() const { return rejected_; }    // candidates with bad end bytes
  std::uint64_t discarded() const { return discarded_; }  // bytes dropped outside accepted frames
  void reset() { used_ = 0; }

 private:
  /// Looks for one frame at the start of the buffer; returns the body length if one is
  /// complete and valid (body at buffer_[4]), 0 if more bytes are needed, and drops bytes
  /// that cannot start a frame or belong to a rejected one.
  std::size_t next_frame();
  void drop(std::size_t count);

  Style style_;
  std::array<std::uint8_t, kBufferSize> buffer_{};
  std::size_t used_ = 0;
  std::uint64_t frames_ = 0;
  std::uint64_t rejected_ = 0;
  std::uint64_t discarded_ = 0;
};

template <class OnBody>
void FrameParser::feed(std::span<const std::uint8_t> bytes, OnBody&& on_body) {
  while (!bytes.empty()) {
    const std::size_t take = std::min(bytes.size(), buffer_.size() - used_);
    for (std::size_t i = 0; i < take; ++i) buffer_[used_ + i] = bytes[i];
    used_ += take;
    bytes = bytes.subspan(take);
    for (std::size_t length = next_frame(); length != 0; length = next_frame()) {
      on_body(std::span<const std::uint8_t>(buffer_.data() + 4, length));
      drop(4 + length);
    }
    if (used_ == buffer_.size()) drop(1);  // a LEN of 255 plus noise cannot fill it; never stall
  }
}

}  // namespace robotd::parol6
