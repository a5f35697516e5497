// Encoding and decoding of the PAROL6 frames of parol6_frames.hpp: the primitives of
// parol6_serial.md §3, the layouts of §4 (host → board) and §5 (board → host), and the stream
// parser of §2.1. Nothing here allocates.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "parol6_frames.hpp"

namespace robotd::parol6 {
namespace {

constexpr std::uint8_t kStartByte = 0xFF;
constexpr std::uint8_t kEndByte1 = 0x01;
constexpr std::uint8_t kEndByte2 = 0x02;
constexpr std::size_t kStartBytes = 3;
constexpr std::size_t kHeaderBytes = kStartBytes + 1;  // start bytes + LEN
constexpr std::size_t kEndBytes = 2;
constexpr std::size_t kInt24Bytes = 3;
constexpr std::uint32_t kInt24Modulus = 0x1000000;
constexpr std::uint32_t kInt24SignBit = 0x800000;

/// Body offsets of the host frame (frame offset − 4, the firmware's data_buffer index), §4.
namespace host {
constexpr std::size_t kPosition = 0;
constexpr std::size_t kSpeed = 18;
constexpr std::size_t kCommand = 36;
constexpr std::size_t kAffectedJoints = 37;
constexpr std::size_t kIo = 38;
constexpr std::size_t kTimeout = 39;
constexpr std::size_t kGripperPosition = 40;
constexpr std::size_t kGripperSpeed = 42;
constexpr std::size_t kGripperCurrent = 44;
constexpr std::size_t kGripperCommand = 46;
constexpr std::size_t kGripperMode = 47;
constexpr std::size_t kGripperId = 48;
constexpr std::size_t kCrc = 49;
constexpr std::size_t kFieldBytes = 50;  // what the firmware reads, whatever LEN says
static_assert(kFieldBytes + kEndBytes == kHostLength);
static_assert(kHeaderBytes + kHostLength == kHostFrameSize);
}  // namespace host

/// Body offsets of the board's reply, §5.
namespace robot {
constexpr std::size_t kPosition = 0;
constexpr std::size_t kSpeed = 18;
constexpr std::size_t kHomed = 36;
constexpr std::size_t kIo = 37;
constexpr std::size_t kTemperatureError = 38;
constexpr std::size_t kPositionError = 39;
constexpr std::size_t kTiming = 40;
constexpr std::size_t kTimeoutError = 42;
constexpr std::size_t kEchoedCommand = 43;
constexpr std::size_t kGripperId = 44;
constexpr std::size_t kGripperPosition = 45;
constexpr std::size_t kGripperSpeed = 47;
constexpr std::size_t kGripperCurrent = 49;
constexpr std::size_t kGripperStatus = 51;
constexpr std::size_t kObjectDetection = 52;
constexpr std::size_t kCrc = 53;
constexpr std::size_t kFieldBytes = 54;
static_assert(kFieldBytes + kEndBytes == kRobotLength);
static_assert(kHeaderBytes + kRobotLength == kRobotFrameSize);
}  // namespace robot

using Body = std::span<std::uint8_t>;
using ConstBody = std::span<const std::uint8_t>;

void put_u16(Body body, std::size_t at, std::uint16_t value) {
  body[at] = static_cast<std::uint8_t>(value >> 8);
  body[at + 1] = static_cast<std::uint8_t>(value);
}
void put_i16(Body body, std::size_t at, std::int16_t value) { put_u16(body, at, static_cast<std::uint16_t>(value)); }
std::uint16_t get_u16(ConstBody body, std::size_t at) {
  return static_cast<std::uint16_t>((body[at] << 8) | body[at + 1]);
}
std::int16_t get_i16(ConstBody body, std::size_t at) { return static_cast<std::int16_t>(get_u16(body, at)); }

void put_joints(Body body, std::size_t at, const std::array<std::int32_t, kJoints>& values) {
  for (const std::int32_t value : values) {
    put_int24(std::span<std::uint8_t, kInt24Bytes>(body.subspan(at, kInt24Bytes)), value);
    at += kInt24Bytes;
  }
}
std::array<std::int32_t, kJoints> get_joints(ConstBody body, std::size_t at) {
  std::array<std::int32_t, kJoints> values{};
  for (std::int32_t& value : values) {
    value = get_int24(std::span<const std::uint8_t, kInt24Bytes>(body.subspan(at, kInt24Bytes)));
    at += kInt24Bytes;
  }
  return values;
}

/// A frame of `kSize` bytes with its start bytes, LEN and end bytes in place, the rest zero.
template <std::size_t kSize>
std::array<std::uint8_t, kSize> envelope() {
  std::array<std::uint8_t, kSize> frame{};
  std::fill_n(frame.begin(), kStartBytes, kStartByte);
  frame[kStartBytes] = static_cast<std::uint8_t>(kSize - kHeaderBytes);
  frame[kSize - 2] = kEndByte1;
  frame[kSize - 1] = kEndByte2;
  return frame;
}

}  // namespace

// --- primitives --------------------------------------------------------------------------------

void put_int24(std::span<std::uint8_t, 3> out, std::int32_t value) {
  const auto bits = static_cast<std::uint32_t>(value) % kInt24Modulus;  // two's complement, mod 2^24
  out[0] = static_cast<std::uint8_t>(bits >> 16);
  out[1] = static_cast<std::uint8_t>(bits >> 8);
  out[2] = static_cast<std::uint8_t>(bits);
}

std::int32_t get_int24(std::span<const std::uint8_t, 3> in) {
  const std::uint32_t bits = (std::uint32_t{in[0]} << 16) | (std::uint32_t{in[1]} << 8) | std::uint32_t{in[2]};
  const auto value = static_cast<std::int32_t>(bits);
  return bits >= kInt24SignBit ? value - static_cast<std::int32_t>(kInt24Modulus) : value;
}

std::uint8_t pack_bits(const std::array<bool, 8>& bits) {
  std::uint8_t byte = 0;
  for (std::size_t k = 0; k < bits.size(); ++k) {
    if (bits[k]) byte = static_cast<std::uint8_t>(byte | (0x80U >> k));
  }
  return byte;
}

std::array<bool, 8> unpack_bits(std::uint8_t byte) {
  std::array<bool, 8> bits{};
  for (std::size_t k = 0; k < bits.size(); ++k) bits[k] = ((static_cast<unsigned>(byte) >> (7 - k)) & 1U) != 0;
  return bits;
}

ObjectDetection object_detection(std::uint8_t gripper_status_byte) {
  const unsigned bit0 = (gripper_status_byte & gripper_status::kObjectBit0) != 0 ? 1U : 0U;
  const unsigned bit1 = (gripper_status_byte & gripper_status::kObjectBit1) != 0 ? 1U : 0U;
  return static_cast<ObjectDetection>(bit0 | (bit1 << 1));
}

bool RobotFrame::joint_homed(int joint) const {
  if (joint < 0 || joint >= kJoints) return false;
  return ((homed >> (7 - joint)) & 1) != 0;
}

bool RobotFrame::all_homed() const {
  constexpr std::uint8_t kAllJoints = 0xFC;  // elements 0..5
  return (homed & kAllJoints) == kAllJoints;
}

// --- frames ------------------------------------------------------------------------------------

std::array<std::uint8_t, kHostFrameSize> encode(const HostFrame& frame) {
  auto bytes = envelope<kHostFrameSize>();
  const Body body = std::span(bytes).subspan(kHeaderBytes);
  put_joints(body, host::kPosition, frame.position_steps);
  put_joints(body, host::kSpeed, frame.speed_steps_s);
  body[host::kCommand] = frame.command;
  body[host::kAffectedJoints] = frame.affected_joints;
  body[host::kIo] = frame.io;
  body[host::kTimeout] = frame.timeout_ms;
  put_i16(body, host::kGripperPosition, frame.gripper_position);
  put_i16(body, host::kGripperSpeed, frame.gripper_speed);
  put_i16(body, host::kGripperCurrent, frame.gripper_current_ma);
  body[host::kGripperCommand] = frame.gripper_command;
  body[host::kGripperMode] = frame.gripper_mode;
  body[host::kGripperId] = frame.gripper_id;
  body[host::kCrc] = frame.crc;
  return bytes;
}

std::array<std::uint8_t, kRobotFrameSize> encode(const RobotFrame& frame) {
  auto bytes = envelope<kRobotFrameSize>();
  const Body body = std::span(bytes).subspan(kHeaderBytes);
  put_joints(body, robot::kPosition, frame.position_steps);
  put_joints(body, robot::kSpeed, frame.speed_steps_s);
  body[robot::kHomed] = frame.homed;
  body[robot::kIo] = frame.io;
  body[robot::kTemperatureError] = frame.temperature_error;
  body[robot::kPositionError] = frame.position_error;
  put_u16(body, robot::kTiming, frame.timing_ticks);
  body[robot::kTimeoutError] = frame.timeout_error;
  body[robot::kEchoedCommand] = frame.echoed_command;
  body[robot::kGripperId] = frame.gripper_id;
  put_i16(body, robot::kGripperPosition, frame.gripper_position);
  put_i16(body, robot::kGripperSpeed, frame.gripper_speed);
  put_i16(body, robot::kGripperCurrent, frame.gripper_current);
  body[robot::kGripperStatus] = frame.gripper_status;
  body[robot::kObjectDetection] = frame.object_detection;
  body[robot::kCrc] = frame.crc;
  return bytes;
}

std::optional<HostFrame> decode_host_body(std::span<const std::uint8_t> body) {
  if (body.size() < host::kFieldBytes + kEndBytes) return std::nullopt;
  HostFrame frame;
  frame.position_steps = get_joints(body, host::kPosition);
  frame.speed_steps_s = get_joints(body, host::kSpeed);
  frame.command = body[host::kCommand];
  frame.affected_joints = body[host::kAffectedJoints];
  frame.io = body[host::kIo];
  frame.timeout_ms = body[host::kTimeout];
  frame.gripper_position = get_i16(body, host::kGripperPosition);
  frame.gripper_speed = get_i16(body, host::kGripperSpeed);
  frame.gripper_current_ma = get_i16(body, host::kGripperCurrent);
  frame.gripper_command = body[host::kGripperCommand];
  frame.gripper_mode = body[host::kGripperMode];
  frame.gripper_id = body[host::kGripperId];
  frame.crc = body[host::kCrc];
  return frame;
}

std::optional<RobotFrame> decode_robot_body(std::span<const std::uint8_t> body) {
  if (body.size() < robot::kFieldBytes + kEndBytes) return std::nullopt;
  RobotFrame frame;
  frame.position_steps = get_joints(body, robot::kPosition);
  frame.speed_steps_s = get_joints(body, robot::kSpeed);
  frame.homed = body[robot::kHomed];
  frame.io = body[robot::kIo];
  frame.temperature_error = body[robot::kTemperatureError];
  frame.position_error = body[robot::kPositionError];
  frame.timing_ticks = get_u16(body, robot::kTiming);
  frame.timeout_error = body[robot::kTimeoutError];
  frame.echoed_command = body[robot::kEchoedCommand];
  frame.gripper_id = body[robot::kGripperId];
  frame.gripper_position = get_i16(body, robot::kGripperPosition);
  frame.gripper_speed = get_i16(body, robot::kGripperSpeed);
  frame.gripper_current = get_i16(body, robot::kGripperCurrent);
  frame.gripper_status = body[robot::kGripperStatus];
  frame.object_detection = body[robot::kObjectDetection];
  frame.crc = body[robot::kCrc];
  return frame;
}

// --- stream parser -----------------------------------------------------------------------------

std::size_t FrameParser::next_frame() {
  for (;;) {
    // Hunt: the first run of three start bytes. `start` is where the current run of FFs begins.
    std::size_t start = 0;
    std::size_t run = 0;
    while (run < kStartBytes && start + run < used_) {
      if (buffer_[start + run] == kStartByte) {
        ++run;
      } else {
        start += run + 1;
        run = 0;
      }
    }
    // Bytes before the run cannot start a frame; a trailing run of one or two FFs may still.
    discarded_ += start;
    drop(start);
    if (run < kStartBytes || used_ < kHeaderBytes) return 0;

    // The byte after the third FF is LEN, whatever its value (a fourth FF makes LEN 255).
    const std::size_t length = buffer_[kStartBytes];
    if (used_ < kHeaderBytes + length) return 0;
    if (length >= kEndBytes && buffer_[kHeaderBytes + length - 2] == kEndByte1 &&
        buffer_[kHeaderBytes + length - 1] == kEndByte2) {
      ++frames_;
      return length;
    }
    // Rejected. The board hunts on after the whole candidate; a resynchronising host only skips
    // its first start byte, so a frame that begins inside the candidate is still found.
    ++rejected_;
    const std::size_t skip = style_ == Style::kFirmware ? kHeaderBytes + length : 1;
    discarded_ += skip;
    drop(skip);
  }
}

void FrameParser::drop(std::size_t count) {
  count = std::min(count, used_);
  const auto first = buffer_.begin() + static_cast<std::ptrdiff_t>(count);
  std::copy(first, buffer_.begin() + static_cast<std::ptrdiff_t>(used_), buffer_.begin());
  used_ -= count;
}

}  // namespace robotd::parol6
