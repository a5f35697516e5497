// The Linux CAN frame conversion (drivers/common/src/can_frame_conversion.hpp) on any datagram a
// SocketCAN socket or the unix-socket stand-in can deliver: a struct can_frame / canfd_frame of
// any length, with any id, flags and len byte. What from_linux accepts must be a message a codec
// may read (length within the frame's limit), and must convert back to the same message.
//
// Input: the datagram, as recv() would fill a canfd_frame (the rest of the struct zero).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "can_frame_conversion.hpp"
#include "fuzz_check.hpp"

namespace {

using robotd::transport::CanMessage;

bool same_message(const CanMessage& a, const CanMessage& b) {
  return a.id == b.id && a.extended == b.extended && a.fd == b.fd && a.bitrate_switch == b.bitrate_switch &&
         a.error_frame == b.error_frame && a.length == b.length &&
         std::equal(a.data.begin(), a.data.begin() + a.length, b.data.begin());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  canfd_frame frame{};
  const std::size_t received = std::min(size, sizeof(frame));  // recv() truncates a longer datagram
  if (received > 0) std::memcpy(&frame, data, received);
  CanMessage message;
  if (!robotd::transport::from_linux(frame, received, message)) return 0;
  FUZZ_CHECK(message.length <= (message.fd ? CANFD_MAX_DLEN : CAN_MAX_DLEN));

  canfd_frame sent{};
  const std::size_t bytes = robotd::transport::to_linux(message, sent);
  CanMessage again;
  FUZZ_CHECK(robotd::transport::from_linux(sent, bytes, again));
  FUZZ_CHECK(same_message(again, message));
  return 0;
}
