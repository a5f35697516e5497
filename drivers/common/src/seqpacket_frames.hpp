// Moving struct can_frame / canfd_frame datagrams over a unix seqpacket socket: shared by both
// ends of the stand-in (the driver's transport and the simulator's bus).
#pragma once

#include <cerrno>
#include <sys/socket.h>

#include "can_frame_conversion.hpp"
#include "robotd/transport/can_transport.hpp"

namespace robotd::transport {

inline CanIo receive_datagram(int socket, CanMessage& out) noexcept {
  canfd_frame frame{};
  const ssize_t bytes = recv(socket, &frame, sizeof(frame), MSG_DONTWAIT);
  if (bytes == 0) return CanIo::kClosed;  // the peer closed the connection
  if (bytes < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? CanIo::kNone : CanIo::kClosed;
  if (!from_linux(frame, static_cast<std::size_t>(bytes), out)) return CanIo::kNone;
  return out.error_frame ? CanIo::kBusError : CanIo::kDone;
}

inline CanIo send_datagram(int socket, const canfd_frame& frame, std::size_t bytes) noexcept {
  const ssize_t written = ::send(socket, &frame, bytes, MSG_DONTWAIT | MSG_NOSIGNAL);
  if (written == static_cast<ssize_t>(bytes)) return CanIo::kDone;
  if (written < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return CanIo::kNone;
  return CanIo::kClosed;
}

inline CanIo send_datagram(int socket, const CanMessage& message) noexcept {
  canfd_frame frame{};
  const std::size_t bytes = to_linux(message, frame);
  return send_datagram(socket, frame, bytes);
}

}  // namespace robotd::transport
