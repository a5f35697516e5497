#pragma once

#include <vector>

#include "robotd/transport/can_transport.hpp"

namespace robotd::transport {

class StandInCanBus final : public CanTransport {
 public:
  explicit StandInCanBus(std::string path) : path_(std::move(path)) {}
  StandInCanBus(const StandInCanBus&) = delete;
  StandInCanBus& operator=(const StandInCanBus&) = delete;
  ~StandInCanBus() override { close(); }

  /// Listens at the path (replacing a stale socket file left by a killed simulator).
  Result<void> open() override;
  void close() noexcept override;
  /// The next frame any node sent (accepting new nodes first); forwarded to the other nodes.
  CanIo receive(CanMessage& out) noexcept override;
  /// To every node. kNone if there is no node to hear it.
  CanIo send(const CanMessage& message) noexcept override;
  std::string describe() const override { return "stand-in bus " + path_; }

 private:
  void accept_nodes() noexcept;
  void forward(const CanMessage& message, int from) noexcept;

  std::string path_;
  int listener_ = -1;
  std::vector<int> nodes_;
  std::size_t next_node_ = 0;  // round robin, so one busy node cannot starve the others
};

}  // namespace robotd::transport
