// CanMessage ⇄ Linux struct can_frame / canfd_frame, shared by the SocketCAN and stand-in
// transports (the stand-in carries the same structs SocketCAN does).
#pragma once

#include <cstring>
#include <linux/can.h>

#include "robotd/transport/can_message.hpp"

namespace robotd::transport {

/// Fills `out` and returns how many bytes of it to transmit (CAN_MTU or CANFD_MTU).
inline std::size_t to_linux(const CanMessage& message, canfd_frame& out) noexcept {
  std::memset(&out, 0, sizeof(out));
  out.can_id = message.id | (message.extended ? CAN_EFF_FLAG : 0U) | (message.error_frame ? CAN_ERR_FLAG : 0U);
  out.len = message.length;
  std::memcpy(out.data, message.data.data(), message.length);
  if (!message.fd) return CAN_MTU;
  out.flags = message.bitrate_switch ? CANFD_BRS : 0;
  return CANFD_MTU;
}

/// Decodes `bytes` received bytes of `in`; false if it is not a frame.
inline bool from_linux(const canfd_frame& in, std::size_t bytes, CanMessage& out) noexcept {
  if (bytes != CAN_MTU && bytes != CANFD_MTU) return false;
  out.fd = bytes == CANFD_MTU;
  out.error_frame = (in.can_id & CAN_ERR_FLAG) != 0;
  out.extended = (in.can_id & CAN_EFF_FLAG) != 0;
  out.id = in.can_id & (out.error_frame ? CAN_ERR_MASK : out.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
  out.length = in.len > (out.fd ? CANFD_MAX_DLEN : CAN_MAX_DLEN) ? 0 : in.len;
  out.bitrate_switch = out.fd && (in.flags & CANFD_BRS) != 0;
  std::memcpy(out.data.data(), in.data, out.length);
  return true;
}

}  // namespace robotd::transport
