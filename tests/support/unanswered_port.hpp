// A TCP port on 127.0.0.1 that never answers a connection attempt, as a controller that is off
// the network: a listener with a backlog of 0 whose one queued connection is never accepted, so
// the kernel drops every further SYN and the connecting side waits for its own timeout.
#pragma once

#include <cstdint>
#include <stdexcept>

#include "robotd/transport/ip_socket.hpp"

namespace robotd::testing {

class UnansweredPort {
 public:
  UnansweredPort() {
    auto listener = transport::listen_tcp(transport::Endpoint{"127.0.0.1", 0}, /*backlog=*/0);
    if (!listener) throw std::runtime_error(listener.error().message);
    listener_ = std::move(listener).value();
    auto bound = transport::local_endpoint(listener_.fd());
    if (!bound) throw std::runtime_error(bound.error().message);
    port_ = bound.value().port;
    auto queued = transport::connect_tcp(bound.value(), std::chrono::seconds(1));
    if (!queued) throw std::runtime_error("filling the accept queue: " + queued.error().message);
    queued_ = std::move(queued).value();
  }

  std::uint16_t port() const { return port_; }

 private:
  transport::Socket listener_;
  transport::Socket queued_;  // fills the accept queue
  std::uint16_t port_ = 0;
};

}  // namespace robotd::testing
