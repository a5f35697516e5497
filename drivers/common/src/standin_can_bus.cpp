#include "standin_can_bus.hpp"

#include <algorithm>
#include <sys/un.h>
#include <system_error>
#include <unistd.h>

#include "robotd/transport/can_bus.hpp"
#include "robotd/transport/unix_socket.hpp"
#include "seqpacket_frames.hpp"
#include "socketcan_transport.hpp"

namespace robotd::transport {

Result<void> StandInCanBus::open() {
  close();
  auto listener = listen_unix_socket(path_, SOCK_SEQPACKET, 8);
  if (!listener) return listener.error();
  listener_ = listener.value();
  return {};
}

void StandInCanBus::close() noexcept {
  for (const int node : nodes_) ::close(node);
  nodes_.clear();
  if (listener_ >= 0) {
    ::close(listener_);
    unlink(path_.c_str());
  }
  listener_ = -1;
}

void StandInCanBus::accept_nodes() noexcept {
  while (listener_ >= 0) {
    const int node = accept4(listener_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (node < 0) return;
    nodes_.push_back(node);
  }
}

CanIo StandInCanBus::receive(CanMessage& out) noexcept {
  if (listener_ < 0) return CanIo::kClosed;
  accept_nodes();
  for (std::size_t tried = 0; tried < nodes_.size(); ++tried) {
    next_node_ = (next_node_ + 1) % nodes_.size();
    const int node = nodes_[next_node_];
    const CanIo result = receive_datagram(node, out);
    if (result == CanIo::kClosed) {  // that node left the bus
      ::close(node);
      nodes_.erase(nodes_.begin() + static_cast<std::ptrdiff_t>(next_node_));
      return CanIo::kNone;
    }
    if (result != CanIo::kNone) {
      forward(out, node);
      return result;
    }
  }
  return CanIo::kNone;
}

CanIo StandInCanBus::send(const CanMessage& message) noexcept {
  if (listener_ < 0) return CanIo::kClosed;
  accept_nodes();
  forward(message, -1);
  return nodes_.empty() ? CanIo::kNone : CanIo::kDone;
}

void StandInCanBus::forward(const CanMessage& message, int from) noexcept {
  canfd_frame frame{};
  const std::size_t bytes = to_linux(message, frame);
  for (const int node : nodes_) {
    if (node != from) (void)send_datagram(node, frame, bytes);  // a full node drops it, as a slow reader would
  }
}

std::unique_ptr<CanTransport> make_can_bus(const CanLinkConfig& config) {
  if (config.kind == CanLinkConfig::Kind::kStandIn) return std::make_unique<StandInCanBus>(config.path);
  return std::make_unique<SocketCanTransport>(config.interface, config.fd);
}

}  // namespace robotd::transport
