#include "robotd/transport/ip_socket.hpp"

#include <algorithm>
#include <arpa/inet.h>
#include <array>
#include <cerrno>
#include <cstdint>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <system_error>
#include <unistd.h>

#include "errno_text.hpp"

namespace robotd::transport {
namespace {

Result<sockaddr_in> ipv4_address(const Endpoint& endpoint) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(endpoint.port);
  if (inet_pton(AF_INET, endpoint.host.c_str(), &address.sin_addr) != 1) {
    return make_error(ErrorCode::kInvalidArgument,
                      "'" + endpoint.host + "' is not an IPv4 address (expected dotted form, e.g. 192.168.1.18)");
  }
  return address;
}

Endpoint endpoint_of(const sockaddr_in& address) {
  std::array<char, INET_ADDRSTRLEN> text{};
  inet_ntop(AF_INET, &address.sin_addr, text.data(), text.size());
  return Endpoint{text.data(), ntohs(address.sin_port)};
}

sockaddr* as_sockaddr(sockaddr_in& address) { return reinterpret_cast<sockaddr*>(&address); }  // NOLINT: sockets API

Result<Socket> open_socket(int type) {
  Socket sock(::socket(AF_INET, type | SOCK_NONBLOCK | SOCK_CLOEXEC, 0));
  if (!sock.is_open()) return make_error(ErrorCode::kTransport, "cannot create a socket (" + errno_text(errno) + ")");
  return sock;
}

Result<Socket> bound(int type, const Endpoint& local, const char* what) {
  auto address = ipv4_address(local);
  if (!address) return address.error();
  auto sock = open_socket(type);
  if (!sock) return sock.error();
  if (type == SOCK_STREAM) {  // a restarted listener gets its port back despite TIME_WAIT connections
    const int yes = 1;
    setsockopt(sock.value().fd(), SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  }
  if (bind(sock.value().fd(), as_sockaddr(address.value()), sizeof(sockaddr_in)) != 0) {
    return make_error(ErrorCode::kNotAvailable,
                      std::string("cannot bind ") + what + " to " + local.to_string() + " (" + errno_text(errno) + ")");
  }
  return std::move(sock).value();
}

}  // namespace

Socket& Socket::operator=(Socket&& other) noexcept {
  if (this != &other) {
    reset();
    fd_ = other.release();
  }
  return *this;
}

int Socket::release() noexcept {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

void Socket::reset() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

Result<Socket> connect_tcp(const Endpoint& peer, std::chrono::milliseconds timeout, const driver::AbortFlag* abort) {
  auto address = ipv4_address(peer);
  if (!address) return address.error();
  auto opened = open_socket(SOCK_STREAM);
  if (!opened) return opened.error();
  Socket sock = std::move(opened).value();
  const int yes = 1;
  setsockopt(sock.fd(), IPPROTO_TCP, TCP_NODELAY, &yes, sizeof(yes));
  const auto unreachable = [&](int error) {
    return make_error(ErrorCode::kNotAvailable,
                      "cannot connect to " + peer.to_string() + " (" + errno_text(error) + ")");
  };
  if (connect(sock.fd(), as_sockaddr(address.value()), sizeof(sockaddr_in)) == 0) return sock;
  if (errno != EINPROGRESS) return unreachable(errno);
  pollfd waiting{.fd = sock.fd(), .events = POLLOUT, .revents = 0};
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int ready = 0;
  while (ready == 0) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) {
      return make_error(ErrorCode::kNotAvailable, "cannot connect to " + peer.to_string() + ": no answer within " +
                                                      std::to_string(timeout.count()) + " ms");
    }
    // With an abort to watch, wait a millisecond at a time.
    ready = ::poll(&waiting, 1, static_cast<int>(abort != nullptr ? std::min<std::int64_t>(left, 1) : left));
    if (ready == 0 && abort != nullptr && abort->requested()) {
      return driver::aborted_error("connecting to " + peer.to_string());
    }
  }
  int error = 0;
  socklen_t length = sizeof(error);
  if (ready < 0)
    error = errno;
  else
    getsockopt(sock.fd(), SOL_SOCKET, SO_ERROR, &error, &length);
  if (error != 0) return unreachable(error);
  return sock;
}

Result<Socket> listen_tcp(const Endpoint& local, int backlog) {
  auto sock = bound(SOCK_STREAM, local, "a TCP listener");
  if (!sock) return sock.error();
  if (::listen(sock.value().fd(), backlog) != 0) {
    return make_error(ErrorCode::kNotAvailable,
                      "cannot listen on " + local.to_string() + " (" + errno_text(errno) + ")");
  }
  return std::move(sock).value();
}

Result<Socket> bind_udp(const Endpoint& local) { return bound(SOCK_DGRAM, local, "a UDP socket"); }

Result<Endpoint> local_endpoint(int fd) {
  sockaddr_in address{};
  socklen_t length = sizeof(address);
  if (getsockname(fd, as_sockaddr(address), &length) != 0) {
    return make_error(ErrorCode::kTransport, "cannot read a socket's local address (" + errno_text(errno) + ")");
  }
  return endpoint_of(address);
}

Result<Endpoint> peer_endpoint(int fd) {
  sockaddr_in address{};
  socklen_t length = sizeof(address);
  if (getpeername(fd, as_sockaddr(address), &length) != 0) {
    return make_error(ErrorCode::kTransport, "cannot read a socket's peer address (" + errno_text(errno) + ")");
  }
  return endpoint_of(address);
}

SendResult send_some(int fd, std::string_view bytes, std::size_t& sent) {
  sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return SendResult::kWouldBlock;
    return SendResult::kClosed;
  }
  return SendResult::kSent;
}

bool wait_readable(int fd, std::chrono::milliseconds timeout) {
  pollfd waiting{.fd = fd, .events = POLLIN, .revents = 0};
  return ::poll(&waiting, 1, static_cast<int>(timeout.count())) > 0;
}

}  // namespace robotd::transport
