// The connection to an xArm control box, run by the link thread: every socket and every frame
// is handled there, never on robotd's RT thread.
//
// - Command port (502): requests from any non-RT thread and the thread's own (servo_j, mode
//   changes, error polls) go out pipelined; replies are matched by transaction id
//   (transaction_table.hpp). Every reply's status byte is watched: a change of its error or
//   warning bit reads get_err_code at once.
// - Report port (30003 or as configured): each packet becomes ArmFeedback.
// - Servo streaming (servo_phase.hpp): while the RT thread's StreamTarget is active the thread
//   puts the arm into servo mode and sends one servo_j per servo period, each joint limited to
//   what the arm accepts per step; when it ends, back to position mode.
// The RT thread only touches the sequence locks, publish_target(), try_feedback(), try_health(),
// and the link thread's eventfd when an e-stop begins (a non-blocking write).
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "codec/xarm_codec.hpp"
#include "driver/transaction_table.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/driver/seqlock.hpp"
#include "robotd/driver/types.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/io_thread.hpp"
#include "robotd/transport/ip_socket.hpp"

namespace robotd::xarm {

struct LinkSettings {
  transport::Endpoint controller;
  transport::Endpoint report;
  ReportKind report_kind = ReportKind::kReal;
  std::chrono::milliseconds connect_timeout{1000};
  std::chrono::milliseconds report_timeout{50};
  std::chrono::milliseconds error_poll_period{100};
  std::chrono::nanoseconds servo_period{4'000'000};
  std::size_t dof = 6;
  bool enable_for_servo = true;  // motion_en(8, 1) when entering servo mode
  int io_priority = 0;
};

/// What the RT thread wants streamed (written every tick by write()).
struct StreamTarget {
  bool active = false;  // a session owns joints: servo mode, servo_j
  bool estop = false;   // robotd's e-stop: set_state(4) once, stream nothing
  JointValues joints_rad{};
};

enum class ServoPhase : std::uint8_t {
  kPosition,  // mode 0: planned moves through the ops
  kEntering,  // [motion_en,] set_mode(1), set_state(0) sent, replies awaited
  kServo,     // streaming servo_j
  kLeaving,   // set_mode(0), set_state(0) sent, replies awaited
};
std::string_view servo_phase_name(ServoPhase phase);

/// The newest feedback, published by the link thread.
struct ArmFeedback {
  std::uint64_t sequence = 0;  // 0: none yet
  JointValues position_rad{};
  JointValues velocity_rad_s{};
  JointValues effort{};  // N·m (or A after the controller was switched to report currents)
  driver::Pose pose{};
  int state = 0;
  int mode = 0;
  std::uint16_t cmd_num = 0;
  int error_code = 0;  // the controller's, from get_err_code or the normal report
  int warning_code = 0;
  ServoPhase phase = ServoPhase::kPosition;
  driver::FaultInfo fault{};  // code 0: nothing wrong
};

struct LinkHealth {
  bool lost = false;
  driver::FaultInfo reason{};
};

struct LinkCounters {
  std::uint64_t reports = 0;
  std::uint64_t bad_reports = 0;
  std::uint64_t requests = 0;
  std::uint64_t timeouts = 0;
  std::uint64_t unmatched = 0;        // replies nobody waited for
  std::uint64_t motion_feedback = 0;  // unsolicited 0xFF frames
  std::uint64_t error_polls = 0;
  std::uint64_t servo_frames = 0;
  std::uint64_t clipped_frames = 0;  // a joint limited to the per-step speed
  std::uint64_t skipped_frames = 0;  // not sent: too many servo_j replies outstanding
  std::uint64_t servo_entries = 0;
  std::int64_t servo_interval_max_ns = 0;
};

class ControllerLink {
 public:
  ControllerLink() = default;
  ControllerLink(const ControllerLink&) = delete;
  ControllerLink& operator=(const ControllerLink&) = delete;
  ~ControllerLink() { close(); }

  /// Connects the command and report ports and starts the link thread. kNotAvailable when the
  /// control box is not reachable. `abort` (maintenance) ends the connection attempts early.
  Result<void> open(const LinkSettings& settings, const driver::AbortFlag* abort = nullptr);
  void close() noexcept;
  bool is_open() const { return io_.running(); }

  /// Sends `request` and waits for its reply. Any non-RT thread; `abort` (maintenance) ends the
  /// wait early (the reply, when it comes, is then dropped).
  Result<Reply> request(const Request& request, std::chrono::milliseconds timeout,
                        const driver::AbortFlag* abort = nullptr);
  /// Re-reads the controller's codes now, and starts servo mode afresh if a session streams
  /// (after recover() reset the arm).
  void restart();

  // RT thread: never waits for the link thread. A try_ that fails (the link thread, preempted by
  // the RT thread, is mid-store) leaves `out` as it was: the caller keeps its previous copy.
  /// An e-stop that begins wakes the link thread, so its stop command goes out now rather than at
  /// the thread's next wake-up (robotd counts the e-stop as delivered once write() returned).
  void publish_target(const StreamTarget& target) noexcept {
    target_.store(target);
    if (target.estop && !published_estop_) io_.wake();
    published_estop_ = target.estop;
  }
  bool try_feedback(ArmFeedback& out) const noexcept { return feedback_.try_load(out); }
  bool try_health(LinkHealth& out) const noexcept { return health_.try_load(out); }

  // Other threads (they may wait for the link thread to finish a store).
  ArmFeedback feedback() const noexcept { return feedback_.load_non_rt(); }
  LinkHealth health() const noexcept { return health_.load_non_rt(); }
  LinkCounters counters() const noexcept { return counters_.load_non_rt(); }

 private:
  struct Outgoing {
    Request request;
    std::chrono::milliseconds timeout;
    TransactionTable::Callback on_reply;
  };

  void run() noexcept;
  void serve(Clock::time_point now);
  void wait_for_io(Clock::time_point now);
  void take_requests(Clock::time_point now);
  void send(const Request& request, Clock::time_point now, std::chrono::milliseconds timeout,
            TransactionTable::Callback on_reply);
  void read_command_port();
  void handle_frame(const Frame& frame);
  void watch_status(const Reply& reply);
  void read_report_port(Clock::time_point now);
  void publish(const Report& report, Clock::time_point now);
  void poll_errors(Clock::time_point now);
  void apply_codes(const ErrorWarning& codes);

  // Servo mode and streaming (servo_stream.cpp).
  void drive_servo(Clock::time_point now);
  void follow_estop(const StreamTarget& target, Clock::time_point now);
  void enter_servo(Clock::time_point now);
  void refuse_servo(const std::string& why);
  void leave_servo(Clock::time_point now);
  /// Sends `requests` pipelined, in order; `done(ok, why)` once all are answered (ok: every one
  /// answered and none refused as invalid).
  void send_sequence(const std::vector<Request>& requests, Clock::time_point now,
                     std::function<void(bool ok, const std::string& why)> done);
  void stream(const StreamTarget& target, Clock::time_point now);
  bool at_rest() const;

  void flush_command_port();
  void lose_link(const std::string& why);
  void wake() const { io_.wake(); }

  LinkSettings settings_;
  transport::Socket command_;
  transport::Socket report_;
  transport::IoThread io_;

  // Between request() callers and the link thread.
  std::mutex queue_mutex_;
  std::vector<Outgoing> queue_;
  std::atomic<bool> restart_requested_{false};

  // Between the RT thread (or readers) and the link thread.
  driver::SeqLock<StreamTarget> target_;
  bool published_estop_ = false;  // RT thread only
  driver::SeqLock<ArmFeedback> feedback_;
  driver::SeqLock<LinkHealth> health_;
  driver::SeqLock<LinkCounters> counters_;

  // Link thread only.
  StreamTarget target_read_;  // the newest target it could read (the RT thread may be mid-store)
  TransactionTable transactions_;
  FrameSplitter frames_;
  ReportSplitter reports_;
  Bytes command_out_;
  LinkCounters link_counters_;
  ArmFeedback latest_;                  // what was last published
  Clock::time_point last_report_at_{};  // {}: none yet
  std::uint64_t feedback_sequence_ = 0;
  ErrorWarning codes_;
  StatusBits last_status_;
  Clock::time_point next_error_poll_at_{};
  bool error_poll_in_flight_ = false;
  ServoPhase phase_ = ServoPhase::kPosition;
  std::uint64_t generation_ = 0;     // of the latest mode change; older replies are stale
  std::uint64_t confirm_after_ = 0;  // entering: replies in, reports after this sequence confirm
  Clock::time_point confirm_deadline_{};
  driver::FaultInfo servo_fault_{};    // why servo mode could not be entered, or was lost
  Clock::time_point stopped_since_{};  // the box has shown a stop under a streaming session since
  Clock::time_point leave_requested_at_{};
  bool estop_sent_ = false;
  Clock::time_point next_estop_probe_at_{};
  Clock::time_point next_servo_at_{};
  Clock::time_point last_servo_at_{};
  JointValues last_sent_{};
  bool lost_ = false;
};

}  // namespace robotd::xarm
