// robotd-xarm-sim's loop: one thread. Every millisecond (absolute CLOCK_MONOTONIC deadlines), at
// each report deadline, and at once when a client writes or connects (it waits in ppoll on the
// listeners and the clients): serve the control channel, accept clients, read their frames and
// answer each (Controller), move the arm to now, send the motion feedback to the clients it
// belongs to, send the reports that are due, write what is queued.
#pragma once

#include <csignal>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/xarm_codec.hpp"
#include "controller.hpp"
#include "report_server.hpp"
#include "robotd/sim_control/control_server.hpp"
#include "robotd/sim_control/sim_clock.hpp"
#include "robotd/transport/ip_socket.hpp"
#include "sim_options.hpp"

namespace robotd::xarm::sim {

class Simulator {
 public:
  Simulator(SimOptions options, const ArmModel& model);

  /// Listens on the command port, the report ports and the control socket; the error says which
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
    FrameSplitter frames;
    std::string output;
    std::uint16_t last_transaction_id = 0;
    std::uint16_t last_protocol = kProtocolPrivate;
    bool closed = false;
  };

  void accept_clients();
  void read_client(Client& client);
  void send(Client& client, const Frame& frame);
  void send_reply(Client& client, const Frame& reply);
  void send_feedback();
  void flush(Client& client);
  void drop_closed_clients();
  void wait_until(std::int64_t wake_ns);

  // control_ops.cpp
  nlohmann::json state() const;
  void send_garbage(const std::string& kind, nlohmann::json& reply);
  void disconnect_clients();

  SimOptions options_;
  Controller controller_;
  transport::Socket listener_;
  std::vector<ReportServer> reports_;
  std::optional<sim_control::ControlServer> control_server_;
  std::vector<Client> clients_;
  ClientId next_client_id_ = 1;

  bool reports_silenced_ = false;
  std::uint64_t replies_to_drop_ = 0;
  std::uint64_t replies_sent_ = 0;
  std::uint64_t replies_dropped_ = 0;
  std::uint64_t feedback_frames_sent_ = 0;
  std::uint64_t garbage_sent_ = 0;
};

using sim_control::monotonic_ns;
using sim_control::to_timespec;

}  // namespace robotd::xarm::sim
