// robotd-imu-sim's loop: a Yesense IMU streaming output frames on a pseudo-terminal at a fixed
// rate, and the control channel tests use to steer it or make it misbehave (README.md).
#pragma once

#include <csignal>
#include <cstdint>
#include <optional>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "body_motion.hpp"
#include "robotd/result.hpp"
#include "robotd/sim_control/control_server.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::imu::sim {

struct SimOptions {
  std::string pty_path;      // --pty: the symlink to the pseudo-terminal's device end
  std::string control_path;  // --control; empty: no control channel
  double rate_hz = 200;      // --rate-hz
  bool quiet = false;
};

class ImuSimulator {
 public:
  explicit ImuSimulator(SimOptions options);

  /// Creates the pty (and its symlink) and the control socket.
  Result<void> open();
  /// Streams until `stop` is set; then closes the pty (its symlink goes) and the socket.
  void run(const volatile std::sig_atomic_t& stop);

 private:
  nlohmann::json control(const nlohmann::json& request);  // control_ops.cpp
  nlohmann::json state(std::int64_t now_ns) const;

  void check_host();
  void send_frame(std::int64_t now_ns);
  void send_garbage();
  bool write_all(const std::uint8_t* bytes, std::size_t count);
  void close_line();
  void reopen_line_if_due(std::int64_t now_ns);
  void log_changes();

  SimOptions options_;
  std::int64_t start_ns_;
  std::int64_t period_ns_;
  transport::PseudoTerminal pty_;
  std::optional<sim_control::ControlServer> control_server_;
  BodyMotion body_;
  std::mt19937 random_{20'240'601};

  bool line_open_ = false;
  bool host_connected_ = false;
  std::optional<std::int64_t> reopen_line_at_ns_;
  std::int64_t paused_until_ns_ = 0;
  std::uint16_t sequence_ = 0;
  std::uint64_t frames_sent_ = 0;
  std::uint64_t frames_dropped_ = 0;  // the host did not read: its buffer was full
  std::uint64_t garbage_pending_ = 0;
  std::uint64_t garbage_sent_ = 0;
  std::uint64_t corrupt_pending_ = 0;
  std::uint64_t frames_corrupted_ = 0;
  std::uint64_t bytes_received_ = 0;  // the host's configuration commands: read and ignored

  bool logged_line_open_ = false;
  bool logged_host_connected_ = false;
};

}  // namespace robotd::imu::sim
