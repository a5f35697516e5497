// robotd-realman-sim's loop: one thread. Every millisecond (absolute CLOCK_MONOTONIC deadlines),
// at each push deadline, and at once when a client writes or connects (it waits in ppoll on the
// listener and the clients): serve the control channel, accept clients, read their lines and
// answer each (Controller), move the arm to now, send the events to the clients they belong to,
// send the UDP push when due, write what is queued.
#pragma once

#include <csignal>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/realman_codec.hpp"
#include "controller.hpp"
#include "robotd/sim_control/control_server.hpp"
#include "robotd/sim_control/sim_clock.hpp"
#include "robotd/transport/ip_socket.hpp"
#include "sim_options.hpp"

namespace robotd::realman::sim {

class Simulator {
 public:
  Simulator(SimOptions options, const ArmModel& model);

  /// Listens on the TCP port, opens the UDP socket and the control socket; the error says which
  /// and why.
  Result<void> open();
  /// Runs the loop until `stop` is non-zero (set from a signal handler).
  void run(const volatile std::sig_atomic_t& stop);

  /// One control-channel request and its reply (control_ops.cpp).
  nlohmann::json control(const nlohmann::json& request);

 private:
  struct Client {
    ClientId id = 0;
    transport::Socket socket;
    transport::Endpoint peer;
    LineSplitter lines;
    std::string output;
    bool closed = false;
  };

  void accept_clients();
  void read_client(Client& client);
  void send_reply(Client& client, const nlohmann::json& reply);
  void send_events();
  void push_if_due(std::int64_t now_ns);
  void flush(Client& client);
  void drop_closed_clients();
  void wait_until(std::int64_t wake_ns);
  /// Where the push goes: the configured ip, else the most recent client's address; nullopt
  /// when neither exists.
  std::optional<transport::Endpoint> push_destination() const;
  bool send_datagram(const transport::Endpoint& destination, std::string_view bytes);

  // control_ops.cpp
  nlohmann::json state(std::int64_t now_ns) const;
  void send_garbage(nlohmann::json& reply);
  void disconnect_clients();

  SimOptions options_;
  Controller controller_;
  transport::Socket listener_;
  transport::Socket udp_;
  std::optional<sim_control::ControlServer> control_server_;
  std::vector<Client> clients_;
  ClientId next_client_id_ = 1;

  std::int64_t next_push_ns_ = 0;
  std::int64_t push_period_ns_ = 0;  // of the schedule in force; a new cycle restarts it
  bool push_silenced_ = false;
  std::uint64_t replies_to_drop_ = 0;

  std::uint64_t clients_accepted_ = 0;
  std::uint64_t replies_sent_ = 0;
  std::uint64_t replies_dropped_ = 0;
  std::uint64_t events_sent_ = 0;
  std::uint64_t pushes_sent_ = 0;
  std::uint64_t push_failures_ = 0;
  std::uint64_t garbage_sent_ = 0;
};

using sim_control::monotonic_ns;
using sim_control::to_timespec;

}  // namespace robotd::realman::sim
