// A CAN link a driver uses from its RT thread: non-blocking send and receive, errors as values.
// Two implementations, chosen by config: SocketCAN (a real or virtual CAN interface) and the
// stand-in (frames over a unix seqpacket socket to a simulator) for machines without AF_CAN.
#pragma once

#include <chrono>
#include <memory>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "robotd/driver/json_reader.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/can_message.hpp"

namespace robotd::transport {

enum class CanIo : std::uint8_t {
  kDone,      // receive: a frame in `out`; send: handed to the kernel
  kNone,      // receive: nothing waiting; send: the transmit queue is full (frame not sent)
  kBusError,  // receive: an error frame from the controller (bus-off, error passive, …) in `out`
  kClosed,    // the link is gone (interface down, simulator exited)
};

class CanTransport {
 public:
  virtual ~CanTransport() = default;

  /// Opens the link; the error says exactly what is wrong and what to do.
  virtual Result<void> open() = 0;
  virtual void close() noexcept = 0;
  /// Non-blocking; RT-safe (one system call, no allocation).
  virtual CanIo receive(CanMessage& out) noexcept = 0;
  virtual CanIo send(const CanMessage& message) noexcept = 0;
  /// "socketcan can0" or "stand-in /run/robotd/piper.sock", for messages.
  virtual std::string describe() const = 0;
};

struct CanLinkConfig {
  enum class Kind { kSocketCan, kStandIn };
  Kind kind = Kind::kSocketCan;
  std::string interface = "can0";  // SocketCAN interface name
  std::string path;                // stand-in socket path
  bool fd = false;                 // enable CAN-FD frames on the socket
};

/// Reads a "can" params object: {"transport": "socketcan", "interface": "can0", "fd": false}
/// or {"transport": "standin", "path": "/tmp/piper.sock"}.
CanLinkConfig read_can_link(JsonReader& reader);

std::unique_ptr<CanTransport> make_can_transport(const CanLinkConfig& config);

/// Decodes a controller error frame (SocketCAN's CAN_ERR_* classes) into words.
std::string describe_bus_error(const CanMessage& error_frame);
/// The same into a NUL-terminated buffer (truncated to fit), for the RT thread: no allocation.
void describe_bus_error(const CanMessage& error_frame, std::span<char> out) noexcept;

}  // namespace robotd::transport
