#pragma once

#include "robotd/transport/can_transport.hpp"

namespace robotd::transport {

/// A raw CAN socket bound to one interface (can0, vcan0, …), non-blocking, with controller
/// error frames enabled so bus errors reach the driver.
class SocketCanTransport final : public CanTransport {
 public:
  SocketCanTransport(std::string interface, bool fd) : interface_(std::move(interface)), fd_(fd) {}
  SocketCanTransport(const SocketCanTransport&) = delete;
  SocketCanTransport& operator=(const SocketCanTransport&) = delete;
  ~SocketCanTransport() override { close(); }

  Result<void> open() override;
  void close() noexcept override;
  CanIo receive(CanMessage& out) noexcept override;
  CanIo send(const CanMessage& message) noexcept override;
  std::string describe() const override { return "socketcan " + interface_; }

 private:
  std::string interface_;
  bool fd_;
  int socket_ = -1;
};

}  // namespace robotd::transport
