#include "robotd/transport/unix_socket.hpp"

#include <cerrno>
#include <sys/socket.h>
#include <sys/un.h>
#include <system_error>
#include <unistd.h>

namespace robotd::transport {

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

}  // namespace robotd::transport
