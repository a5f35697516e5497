// A CAN message read from a fuzzer's input (fuzz_input.hpp), for the targets of CAN codecs.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "robotd/transport/can_message.hpp"

namespace robotd::fuzz {

/// Flag bits of the first byte of read_can_message.
namespace can_flag {
inline constexpr std::uint8_t kExtended = 0x01;
inline constexpr std::uint8_t kFd = 0x02;
inline constexpr std::uint8_t kBitrateSwitch = 0x04;
inline constexpr std::uint8_t kErrorFrame = 0x08;
}  // namespace can_flag

/// A CAN message as a transport can hand one over: flags u8 (can_flag), id u32 LE (masked to 29
/// bits), length u8 (at most 8, or 64 on an FD frame), then that many data bytes (zeros once the
/// input runs out). Seed files are written in this layout.
inline transport::CanMessage read_can_message(FuzzInput& input) {
  transport::CanMessage message;
  const std::uint8_t flags = input.u8();
  message.extended = (flags & can_flag::kExtended) != 0;
  message.fd = (flags & can_flag::kFd) != 0;
  message.bitrate_switch = message.fd && (flags & can_flag::kBitrateSwitch) != 0;
  message.error_frame = (flags & can_flag::kErrorFrame) != 0;
  message.id = input.u32_le() & 0x1FFF'FFFFU;
  const std::size_t max_length = message.fd ? message.data.size() : 8;
  message.length = static_cast<std::uint8_t>(std::min<std::size_t>(input.u8(), max_length));
  const auto data = input.take(message.length);
  std::copy(data.begin(), data.end(), message.data.begin());
  return message;
}

}  // namespace robotd::fuzz
