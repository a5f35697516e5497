// One CAN or CAN-FD frame as codecs see it: identifier, flags and payload, independent of
// how the frame travels (SocketCAN, the unix-socket stand-in, a USB adapter).
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace robotd::transport {

struct CanMessage {
  std::uint32_t id = 0;   // 11-bit standard or 29-bit extended identifier, without flag bits
  bool extended = false;  // 29-bit identifier
  bool fd = false;        // CAN-FD frame (up to 64 bytes); classic frames carry up to 8
  bool bitrate_switch = false;
  bool error_frame = false;  // a controller error report: id holds the CAN_ERR_* class bits
  std::uint8_t length = 0;
  std::array<std::uint8_t, 64> data{};

  std::span<const std::uint8_t> payload() const { return {data.data(), length}; }
};

/// A classic 8-byte frame with a standard identifier (the common case for arms).
inline CanMessage classic_frame(std::uint32_t id, std::span<const std::uint8_t> bytes) {
  CanMessage message;
  message.id = id;
  message.length = static_cast<std::uint8_t>(bytes.size() > 8 ? 8 : bytes.size());
  for (std::size_t i = 0; i < message.length; ++i) message.data[i] = bytes[i];
  return message;
}

}  // namespace robotd::transport
