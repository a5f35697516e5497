#include "standin_can_transport.hpp"

#include <sys/un.h>
#include <system_error>
#include <unistd.h>

#include "seqpacket_frames.hpp"

namespace robotd::transport {

Result<void> StandInCanTransport::open() {
  close();
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path_.empty() || path_.size() >= sizeof(address.sun_path)) {
    return make_error(ErrorCode::kInvalidArgument, "stand-in CAN path '" + path_ + "' is empty or too long");
  }
  path_.copy(address.sun_path, sizeof(address.sun_path) - 1);
  const int sock = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
  if (sock < 0) return make_error(ErrorCode::kTransport, "cannot create a unix socket");
  if (connect(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {  // NOLINT
    const int error = errno;
    ::close(sock);
    return make_error(ErrorCode::kNotAvailable, "no CAN bus at " + path_ + " (" +
                                                    std::generic_category().message(error) +
                                                    "): is the simulator running and listening there?");
  }
  socket_ = sock;
  return {};
}

void StandInCanTransport::close() noexcept {
  if (socket_ >= 0) ::close(socket_);
  socket_ = -1;
}

CanIo StandInCanTransport::receive(CanMessage& out) noexcept {
  return socket_ < 0 ? CanIo::kClosed : receive_datagram(socket_, out);
}

CanIo StandInCanTransport::send(const CanMessage& message) noexcept {
  return socket_ < 0 ? CanIo::kClosed : send_datagram(socket_, message);
}

}  // namespace robotd::transport
