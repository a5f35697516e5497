// TCP and UDP over IPv4 for controllers on Ethernet (RealMan, xArm): a client connection with a
// connect timeout, a listener for simulators, a UDP socket for datagram pushes. Every socket is
// non-blocking and close-on-exec; errors say which address failed and why.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "robotd/driver/abort_flag.hpp"
#include "robotd/result.hpp"

namespace robotd::transport {

struct Endpoint {
  std::string host;  // dotted IPv4 ("192.168.1.18", "127.0.0.1")
  std::uint16_t port = 0;

  std::string to_string() const { return host + ":" + std::to_string(port); }
};

/// Owns a socket descriptor; closes it on destruction.
class Socket {
 public:
  Socket() = default;
  explicit Socket(int fd) : fd_(fd) {}
  Socket(Socket&& other) noexcept : fd_(other.release()) {}
  Socket& operator=(Socket&& other) noexcept;
  Socket(const Socket&) = delete;
  Socket& operator=(const Socket&) = delete;
  ~Socket() { reset(); }

  int fd() const { return fd_; }
  bool is_open() const { return fd_ >= 0; }
  int release() noexcept;
  void reset() noexcept;

 private:
  int fd_ = -1;
};

/// Connects to `peer` within `timeout`, with TCP_NODELAY (small JSON messages must not wait for
/// Nagle). kNotAvailable when nothing answers (refused, unreachable, timed out): the controller
/// may come later. kInvalidArgument for an address that is not dotted IPv4. With `abort`, the
/// wait looks at it every millisecond and ends with driver::aborted_error when it is requested.
Result<Socket> connect_tcp(const Endpoint& peer, std::chrono::milliseconds timeout,
                           const driver::AbortFlag* abort = nullptr);

/// Listens on `local` (port 0: any free port); SO_REUSEADDR so a restarted simulator gets its
/// port back at once.
Result<Socket> listen_tcp(const Endpoint& local, int backlog = 4);

/// A UDP socket bound to `local` (port 0: any free port).
Result<Socket> bind_udp(const Endpoint& local);

/// The address a socket is bound to (its local end).
Result<Endpoint> local_endpoint(int fd);
/// The address of a connected socket's peer.
Result<Endpoint> peer_endpoint(int fd);

enum class SendResult : std::uint8_t { kSent, kWouldBlock, kClosed };
/// Sends as much of `bytes` as the socket takes now; `sent` says how much. kClosed when the peer
/// is gone (EPIPE, ECONNRESET); never raises SIGPIPE.
SendResult send_some(int fd, std::string_view bytes, std::size_t& sent);

/// Waits until `fd` is readable (POLLIN) or `timeout`; false on timeout.
bool wait_readable(int fd, std::chrono::milliseconds timeout);

}  // namespace robotd::transport
