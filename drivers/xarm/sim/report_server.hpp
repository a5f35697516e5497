// One report port (spec §5): a listener whose clients only read, and the packets they get on an
// absolute schedule at the port's rate (a late packet is skipped, not bursted). Polled from the
// simulator's loop.
#pragma once

#include <cstdint>
#include <poll.h>
#include <string>
#include <vector>

#include "codec/xarm_codec.hpp"
#include "controller.hpp"
#include "robotd/transport/ip_socket.hpp"

namespace robotd::xarm::sim {

class ReportServer {
 public:
  /// Serves `kind` on `listener`, the first packet due at `now_ns`.
  ReportServer(ReportKind kind, transport::Socket listener, bool with_force_torque, std::int64_t now_ns);

  static std::int64_t period_ns(ReportKind kind);  // 10 ms real, 200 ms normal, 4 ms realtime
  ReportKind kind() const { return kind_; }
  std::int64_t next_due_ns() const { return next_due_ns_; }

  /// Accepts new clients, and reads (and drops) what clients send, to notice them leave.
  void serve();
  /// When due: one packet of the controller's state to every client (none while `silenced`).
  void publish_if_due(std::int64_t now_ns, const Controller& controller, bool silenced);
  /// Writes what is queued; drops the clients that left or read nothing for too long.
  void flush();
  void disconnect_all();
  void add_poll_fds(std::vector<pollfd>& fds) const;

  std::size_t clients() const { return clients_.size(); }
  std::uint64_t packets_sent() const { return packets_sent_; }

 private:
  struct Client {
    transport::Socket socket;
    std::string output;
    bool closed = false;
  };

  ReportKind kind_;
  transport::Socket listener_;
  bool with_force_torque_;
  std::int64_t period_ns_;
  std::int64_t next_due_ns_;
  std::vector<Client> clients_;
  std::uint64_t packets_sent_ = 0;
};

}  // namespace robotd::xarm::sim
