// The PAROL6 arm behind its control board's USB serial line (docs/drivers/parol6.md).
//
// RT thread: read() drains the serial line into the resynchronising frame parser and turns
// each reply into feedback (positions from the step counters, speeds from their change over the
// board's own timing field, the E-stop input); write() sends one frame per exchange period
// (frame_planner.hpp) and reports a board that stopped answering or a closed line as a lost link.
// Other threads: ops hand one-shot commands, peripheral set points and planned moves over
// through atomics, a sequence lock and the trajectory buffer; never a lock the RT thread takes.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "codec/parol6_frames.hpp"
#include "driver/frame_planner.hpp"
#include "driver/parol6_params.hpp"
#include "driver/trajectory_buffer.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/driver/driver.hpp"
#include "robotd/driver/seqlock.hpp"
#include "robotd/transport/serial_port.hpp"

namespace robotd::parol6 {

inline constexpr std::int32_t kNotConnectedFault = -1;
inline constexpr std::int32_t kLinkLostFault = -2;

/// What the RT thread publishes after every read() for diagnostics() and the ops.
struct BoardSnapshot {
  bool link_up = false;
  bool have_reply = false;
  RobotFrame reply;                    // the newest
  std::uint8_t last_command_sent = 0;  // the command byte of the newest frame sent
  bool session_streaming = false;
  bool estop = false;  // robotd's e-stop as of the last write()
  std::uint64_t frames_sent = 0;
  std::uint64_t replies = 0;
  std::uint64_t rejected = 0;   // candidate frames with bad end bytes
  std::uint64_t discarded = 0;  // bytes skipped to resynchronise
};

class Parol6Driver final : public driver::Driver {
 public:
  Result<void> configure(const nlohmann::json& params) override;
  driver::DeviceDescription describe() const override;

  Result<void> connect() override;
  void disconnect() noexcept override;
  Result<void> recover() override;
  Result<void> reset_zero(std::span<const int> joints) override;
  void abort_maintenance() noexcept override { abort_.request(); }

  driver::IoResult read(driver::Feedback& out, driver::FaultInfo& fault) noexcept override;
  driver::IoResult write(const driver::CommandFrame& command, driver::FaultInfo& fault) noexcept override;

  Result<nlohmann::json> call(const std::string& op, const nlohmann::json& args) override;
  driver::Diagnostics diagnostics() const override;

 private:
  friend class Parol6Ops;

  // Link (non-RT, loop paused or not running).
  Result<void> connect_locked();
  Result<void> open_and_check_link();
  /// Sends IDLE frames until the board answers (it only ever answers).
  Result<void> await_first_reply(std::chrono::milliseconds timeout);
  void send_final_idle() noexcept;

  // RT helpers.
  driver::IoResult link_lost(driver::FaultInfo& fault, const char* why) noexcept;
  /// Reads what is waiting; true when a new reply arrived. `closed`: the line is gone.
  bool drain_replies(std::int64_t now_ns, bool& closed) noexcept;
  void apply_reply(std::span<const std::uint8_t> body, std::int64_t now_ns) noexcept;
  void fill_feedback(driver::Feedback& out) noexcept;
  bool send_frame(const HostFrame& frame) noexcept;
  void publish_snapshot() noexcept;

  BoardSnapshot snapshot() const { return snapshot_.load_non_rt(); }

  Parol6Params params_;
  bool configured_ = false;
  std::unique_ptr<transport::SerialPort> port_;
  std::array<char, 96> link_name_{};
  std::mutex link_mutex_;    // connect / recover / disconnect; never taken by the RT thread
  std::mutex ops_mutex_;     // one op at a time
  driver::AbortFlag abort_;  // abort_maintenance(): connect and recover stop waiting

  // Shared with the ops.
  std::atomic<bool> connected_{false};
  std::atomic<bool> link_lost_{false};
  std::atomic<OneShot> one_shot_{OneShot::kNone};
  std::atomic<std::uint8_t> gripper_mode_once_{0};  // sent in one frame, then back to operate
  std::mutex peripherals_writer_mutex_;             // serialises op writers; RT only try-loads
  driver::SeqLock<Peripherals> peripherals_;
  TrajectoryBuffer trajectory_;
  driver::SeqLock<BoardSnapshot> snapshot_;

  // RT thread (and connect/recover while the loop is paused).
  FrameParser parser_{FrameParser::Style::kResync};
  FramePlanner planner_;
  Peripherals rt_peripherals_;
  RobotFrame reply_;
  bool have_reply_ = false;
  bool have_previous_reply_ = false;
  RobotFrame previous_reply_;
  std::uint64_t replies_ = 0;
  std::uint64_t frames_sent_ = 0;
  std::int64_t last_reply_ns_ = 0;
  std::int64_t next_exchange_ns_ = 0;
  std::int64_t last_frame_ns_ = 0;       // when a frame last went out
  bool reply_pending_delivery_ = false;  // connect()'s reply, not yet read()
  std::int64_t exchange_period_ns_ = 10'000'000;
  std::uint8_t last_command_sent_ = 0;
  bool estop_ = false;
  std::array<double, kJoints> velocity_rad_s_{};
  driver::FaultInfo lost_fault_;
  driver::FaultInfo not_connected_fault_;
};

}  // namespace robotd::parol6
