#pragma once

#include "robotd/transport/can_transport.hpp"

namespace robotd::transport {

/// The stand-in for machines without AF_CAN: the driver end of a unix SOCK_SEQPACKET
/// connection to a simulator's bus (StandInCanBus). Each datagram is one struct can_frame
/// or canfd_frame, exactly what a raw CAN socket carries, so codecs and drivers run unchanged.
class StandInCanTransport final : public CanTransport {
 public:
  explicit StandInCanTransport(std::string path) : path_(std::move(path)) {}
  StandInCanTransport(const StandInCanTransport&) = delete;
  StandInCanTransport& operator=(const StandInCanTransport&) = delete;
  ~StandInCanTransport() override { close(); }

  Result<void> open() override;
  void close() noexcept override;
  CanIo receive(CanMessage& out) noexcept override;
  CanIo send(const CanMessage& message) noexcept override;
  std::string describe() const override { return "stand-in " + path_; }

 private:
  std::string path_;
  int socket_ = -1;
};

}  // namespace robotd::transport
