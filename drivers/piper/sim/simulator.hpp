// robotd-piper-sim's loop: one thread, every millisecond (CLOCK_MONOTONIC, absolute sleeps):
// serve the control channel, take every frame off the bus (answering what the arm answers),
// step the arm to the current time in 1 ms steps, send the feedback that is due (≈ 3040
// frames/s at the default 200 Hz), and carry out the misbehaviour tests asked for.
#pragma once

#include <csignal>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include <nlohmann/json.hpp>

#include "arm_model.hpp"
#include "controller.hpp"
#include "robotd/sim_control/control_server.hpp"
#include "robotd/sim_control/sim_clock.hpp"
#include "robotd/transport/can_transport.hpp"
#include "sim_options.hpp"

namespace robotd::piper::sim {

class Simulator {
 public:
  explicit Simulator(SimOptions options);

  /// Opens the bus and the control socket; the error says which and why.
  Result<void> open();
  /// Runs the loop until `stop` is non-zero (set from a signal handler).
  void run(const volatile std::sig_atomic_t& stop);

  /// One control-channel request and its reply (control_ops.cpp).
  nlohmann::json control(const nlohmann::json& request);

  /// What the arm does at power-up: motors off, standby, settings kept; the stored
  /// MasterSlaveConfig (0x470) takes effect (role and id offsets), as the arm takes it at a restart.
  void restart();

 private:
  struct Summary {  // what is logged when it changes
    ControlMode ctrl_mode = ControlMode::kStandby;
    MoveMode move_mode = MoveMode::kP;
    bool mit = false;
    bool estop = false;
    std::uint8_t enabled_bits = 0;
    std::uint8_t arm_status = 0;
    bool operator==(const Summary&) const = default;
  };

  void poll_bus();
  void step_physics(std::int64_t now_ns);
  void send_feedback(std::int64_t now_ns);
  void send_garbage();
  void reopen_bus_if_due(std::int64_t now_ns);
  void send(const CanMessage& message);
  void log_changes();
  Summary summary() const;

  // control_ops.cpp
  nlohmann::json state() const;
  nlohmann::json raise_error(const nlohmann::json& request);

  SimOptions options_;
  CodecOptions codec_;   // with the id offsets in force
  bool leader_ = false;  // the role in force
  ArmModel arm_;
  Controller controller_;
  std::unique_ptr<transport::CanTransport> bus_;
  std::optional<sim_control::ControlServer> control_server_;
  std::vector<CanMessage> outgoing_;

  std::int64_t physics_ns_ = 0;
  std::int64_t next_high_rate_ns_ = 0;
  std::int64_t next_low_rate_ns_ = 0;
  std::int64_t high_rate_period_ns_ = 0;
  std::int64_t low_rate_period_ns_ = 0;

  // Misbehaviour asked for over the control channel.
  std::int64_t silent_until_ns_ = 0;
  bool drop_replies_ = false;
  bool bus_open_ = false;
  std::optional<std::int64_t> reopen_bus_at_ns_;
  std::int64_t garbage_pending_ = 0;
  std::mt19937 random_{0x5EED};

  std::map<std::uint32_t, std::uint64_t> frames_received_;  // by id (standard ids)
  std::uint64_t frames_sent_ = 0;
  // CLOCK_MONOTONIC when the 0x150 frame that put the arm in e-stop was taken off the bus.
  std::int64_t estop_since_ns_ = 0;
  Summary logged_;
};

using sim_control::monotonic_ns;
using sim_control::to_timespec;

}  // namespace robotd::piper::sim
