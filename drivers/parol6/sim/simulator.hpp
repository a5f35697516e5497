// robotd-parol6-sim's loop: one thread. Every millisecond (absolute CLOCK_MONOTONIC deadlines)
// and whenever bytes arrive from the host (it waits in ppoll on the pty while one is there):
// serve the control channel, run the board's main loop up to now, read the line, answer each
// valid frame with one reply, send the garbage tests asked for.
#pragma once

#include <array>
#include <csignal>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "board.hpp"
#include "codec/parol6_frames.hpp"
#include "line_faults.hpp"
#include "robotd/sim_control/control_server.hpp"
#include "robotd/sim_control/sim_clock.hpp"
#include "robotd/transport/serial_port.hpp"
#include "sim_options.hpp"

namespace robotd::parol6::sim {

class Simulator {
 public:
  explicit Simulator(SimOptions options);

  /// Creates the pty (and its symlink) and the control socket; the error says which and why.
  Result<void> open();
  /// Runs the loop until `stop` is non-zero (set from a signal handler).
  void run(const volatile std::sig_atomic_t& stop);

  /// One control-channel request and its reply (control_ops.cpp).
  nlohmann::json control(const nlohmann::json& request);

 private:
  struct Summary {  // what is logged when it changes
    std::uint8_t command = 0;
    bool disabled = false;
    std::uint8_t homed_mask = 0;
    HomingSequence::Phase homing = HomingSequence::Phase::kIdle;
    bool host_connected = false;
    bool line_open = false;
    bool estop_pressed = false;
    bool operator==(const Summary&) const = default;
  };

  void read_line(std::int64_t now_ns);
  void on_frame(std::span<const std::uint8_t> body, std::int64_t now_ns);
  void send_reply(const RobotFrame& reply);
  void send_garbage();
  void close_line();
  void reopen_line_if_due(std::int64_t now_ns);
  void wait_until(std::int64_t wake_ns);
  void log_changes();
  Summary summary() const;

  // control_ops.cpp
  nlohmann::json state() const;
  void reset_counters();

  SimOptions options_;
  Board board_;
  transport::PseudoTerminal pty_;
  FrameParser parser_{FrameParser::Style::kFirmware};
  /// The firmware's receive buffer: a frame's LEN bytes overwrite its start, the rest keeps
  /// older bytes, and the fields are read at fixed offsets whatever LEN said.
  std::array<std::uint8_t, 256> data_buffer_{};
  std::optional<sim_control::ControlServer> control_server_;
  LineFaults faults_;

  bool line_open_ = false;
  bool host_connected_ = false;  // a process holds the device end open
  std::optional<std::int64_t> reopen_line_at_ns_;
  std::int64_t silent_until_ns_ = 0;

  std::uint64_t bytes_received_ = 0;
  std::uint64_t frames_received_ = 0;    // valid frames (end bytes 01 02)
  std::int64_t command_since_ns_ = 0;    // CLOCK_MONOTONIC: the frame that brought the command in force
  std::uint64_t rejected_base_ = 0;      // parser_.rejected() at the last reset_counters
  std::uint64_t frames_unanswered_ = 0;  // valid frames read during a silence
  std::uint64_t replies_sent_ = 0;
  std::uint64_t replies_dropped_ = 0;  // the host's input buffer was full
  Summary logged_;
};

using sim_control::monotonic_ns;
using sim_control::to_timespec;

}  // namespace robotd::parol6::sim
