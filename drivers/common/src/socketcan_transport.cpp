#include "socketcan_transport.hpp"

#include <cerrno>
#include <cstring>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <system_error>
#include <unistd.h>

#include "can_frame_conversion.hpp"
#include "errno_text.hpp"

namespace robotd::transport {

Result<void> SocketCanTransport::open() {
  close();
  const int sock = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (sock < 0) {
    const int error = errno;
    return make_error(ErrorCode::kNotAvailable,
                      "cannot open a CAN socket (" + errno_text(error) +
                          (error == EAFNOSUPPORT ? "): this kernel has no SocketCAN (AF_CAN); load the can and can_raw "
                                                   "modules, or use the stand-in transport with a simulator"
                                                 : ")"));
  }
  const auto fail = [&](std::string message) {
    ::close(sock);
    return make_error(ErrorCode::kNotAvailable, std::move(message));
  };
  ifreq request{};
  interface_.copy(request.ifr_name, IFNAMSIZ - 1);
  if (ioctl(sock, SIOCGIFINDEX, &request) < 0) {
    return fail("no CAN interface '" + interface_ + "' (" + errno_text(errno) +
                "): is the adapter plugged in? See `ip -details link show`");
  }
  const int index = request.ifr_ifindex;
  if (ioctl(sock, SIOCGIFFLAGS, &request) == 0 && (request.ifr_flags & IFF_UP) == 0) {
    return fail("CAN interface '" + interface_ + "' is down: bring it up with `sudo ip link set " + interface_ +
                " up type can bitrate 1000000`");
  }
  const can_err_mask_t errors = CAN_ERR_MASK;
  setsockopt(sock, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof(errors));
  if (fd_) {
    const int enable = 1;
    if (setsockopt(sock, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &enable, sizeof(enable)) != 0) {
      return fail("CAN interface '" + interface_ + "' cannot carry CAN-FD frames (" + errno_text(errno) +
                  "): configure it with `ip link set " + interface_ +
                  " type can bitrate 1000000 dbitrate 5000000 fd on`");
    }
  }
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = index;
  if (bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {  // NOLINT
    return fail("cannot bind to CAN interface '" + interface_ + "' (" + errno_text(errno) + ")");
  }
  socket_ = sock;
  return {};
}

void SocketCanTransport::close() noexcept {
  if (socket_ >= 0) ::close(socket_);
  socket_ = -1;
}

CanIo SocketCanTransport::receive(CanMessage& out) noexcept {
  if (socket_ < 0) return CanIo::kClosed;
  canfd_frame frame{};
  const ssize_t bytes = ::read(socket_, &frame, sizeof(frame));
  if (bytes < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? CanIo::kNone : CanIo::kClosed;
  if (!from_linux(frame, static_cast<std::size_t>(bytes), out)) return CanIo::kNone;
  return out.error_frame ? CanIo::kBusError : CanIo::kDone;
}

CanIo SocketCanTransport::send(const CanMessage& message) noexcept {
  if (socket_ < 0) return CanIo::kClosed;
  canfd_frame frame{};
  const std::size_t bytes = to_linux(message, frame);
  const ssize_t written = ::write(socket_, &frame, bytes);
  if (written == static_cast<ssize_t>(bytes)) return CanIo::kDone;
  if (written < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS || errno == EINTR)) {
    return CanIo::kNone;
  }
  return CanIo::kClosed;
}

}  // namespace robotd::transport
