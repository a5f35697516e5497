#include "robotd/transport/unix_socket.hpp"

#include <cerrno>
#include <sys/socket.h>
#include <sys/un.h>
#include <system_error>
#include <unistd.h>

namespace robotd::transport {
namespace {

bool fill_address(const std::string& path, sockaddr_un& address) {
  address = sockaddr_un{};
  address.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof(address.sun_path)) return false;
  path.copy(address.sun_path, sizeof(address.sun_path) - 1);
  return true;
}

bool can_connect(const std::string& path, int type) {
  sockaddr_un address{};
  if (!fill_address(path, address)) return false;
  const int sock = socket(AF_UNIX, type | SOCK_CLOEXEC, 0);
  if (sock < 0) return false;
  const bool connected = connect(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;  // NOLINT
  ::close(sock);
  return connected;
}

}  // namespace

Result<int> listen_unix_socket(const std::string& path, int type, int backlog) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof(address.sun_path)) {
    return make_error(ErrorCode::kInvalidArgument, "unix socket path '" + path + "' is empty or too long (at most " +
                                                       std::to_string(sizeof(address.sun_path) - 1) + " characters)");
  }
  path.copy(address.sun_path, sizeof(address.sun_path) - 1);
  const int sock = socket(AF_UNIX, type | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (sock < 0) return make_error(ErrorCode::kTransport, "cannot create a unix socket");
  unlink(path.c_str());
  if (bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||  // NOLINT: the sockets API
      listen(sock, backlog) != 0) {
    const int error = errno;
    ::close(sock);
    return make_error(ErrorCode::kNotAvailable,
                      "cannot listen at " + path + " (" + std::generic_category().message(error) + ")");
  }
  return sock;
}

bool unix_socket_in_use(const std::string& path) {
  return can_connect(path, SOCK_STREAM) || can_connect(path, SOCK_SEQPACKET);
}

}  // namespace robotd::transport
