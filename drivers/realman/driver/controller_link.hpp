// The connection to a RealMan controller, run by the link thread: all socket I/O and all JSON
// happen there, never on robotd's RT thread (JSON allocates; sockets may block).
//
// - TCP (port 8080): requests from any non-RT thread go out in order; replies and
//   current_trajectory_state events are matched to them by key (request_tracker.hpp).
// - UDP: the controller's real-time push is parsed into ArmFeedback; without the push the
//   thread polls get_current_arm_state instead.
// - Streaming: every command period the thread takes the RT thread's latest StreamTarget and
//   sends one movej_canfd, each joint limited to what pass-through accepts per frame.
// The RT thread only touches the sequence locks, publish_target(), try_feedback(), try_health(),
// and the link thread's eventfd when an e-stop begins (a non-blocking write).
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/realman_codec.hpp"
#include "driver/request_tracker.hpp"
#include "robotd/driver/abort_flag.hpp"
#include "robotd/driver/seqlock.hpp"
#include "robotd/driver/types.hpp"
#include "robotd/result.hpp"
#include "robotd/transport/io_thread.hpp"
#include "robotd/transport/ip_socket.hpp"

namespace robotd::realman {

struct LinkSettings {
  transport::Endpoint controller;
  std::chrono::milliseconds connect_timeout{1000};
  std::size_t dof = 6;
  bool push = true;
  transport::Endpoint push_local;  // host "" = the TCP connection's local address
  int push_cycle = 1;
  bool push_joint_speed = false;
  SpeedUnit speed_unit = SpeedUnit::kCentiDegreesPerSecond;
  std::chrono::milliseconds poll_period{20};
  std::chrono::milliseconds feedback_timeout{100};
  std::chrono::nanoseconds command_period{5'000'000};
  PassThrough pass_through;
  int io_priority = 0;
};

/// What the RT thread wants streamed (written every tick by write()).
struct StreamTarget {
  bool active = false;  // a session owns joints: stream movej_canfd
  bool estop = false;   // robotd's e-stop: send set_arm_stop once, stream nothing
  JointValues joints_rad{};
};

/// The newest feedback, published by the link thread.
struct ArmFeedback {
  std::uint64_t sequence = 0;  // 0: none yet
  JointValues position_rad{};
  JointValues velocity_rad_s{};
  std::array<bool, kMaxDof> enabled{};
  bool has_pose = false;
  driver::Pose pose{};
  std::array<std::uint16_t, kMaxDof> joint_errors{};  // each joint's error bits (§7.2)
  driver::FaultInfo fault{};                          // code 0: the controller reports no error
};

struct LinkHealth {
  bool lost = false;
  driver::FaultInfo reason{};
};

struct LinkCounters {
  std::uint64_t pushes = 0;
  std::uint64_t bad_pushes = 0;
  std::uint64_t polls = 0;
  std::uint64_t stream_frames = 0;
  std::uint64_t clipped_frames = 0;  // a joint limited to the per-frame step
  std::uint64_t requests = 0;
  std::uint64_t unmatched = 0;  // replies or events nobody waited for
  std::uint64_t bad_lines = 0;  // TCP lines that were not JSON objects, or oversized
  std::int64_t stream_interval_max_ns = 0;
};

struct RequestOptions {
  std::chrono::milliseconds reply_timeout{1000};
  std::optional<Device> completion;  // wait for this device's current_trajectory_state too
  std::chrono::milliseconds completion_timeout{60'000};
  const driver::AbortFlag* abort = nullptr;  // maintenance: ends the waits early
};

class ControllerLink {
 public:
  ControllerLink() = default;
  ControllerLink(const ControllerLink&) = delete;
  ControllerLink& operator=(const ControllerLink&) = delete;
  ~ControllerLink() { close(); }

  /// Connects TCP, binds the push socket and starts the link thread. kNotAvailable when the
  /// controller is not reachable. `abort` (maintenance) ends the connection attempt early.
  Result<void> open(const LinkSettings& settings, const driver::AbortFlag* abort = nullptr);
  void close() noexcept;
  bool is_open() const { return io_.running(); }

  struct Reply {
    nlohmann::json body;
    std::optional<TrajectoryEvent> completion;  // when RequestOptions::completion was set
  };
  /// Sends `message` and waits for its reply (and completion, if asked). Any non-RT thread.
  Result<Reply> request(const nlohmann::json& message, const RequestOptions& options);
  /// The same, without waiting: the result is only counted (used for stops from the link thread).
  void send_unawaited(const nlohmann::json& message);

  /// Where the controller is asked to push (this PC's address and the bound port).
  const transport::Endpoint& push_endpoint() const { return push_endpoint_; }
  /// Clears the stream's start point: the next active target starts from the measured joints.
  void restart_stream() noexcept { restart_stream_.store(true, std::memory_order_release); }
  /// A slow stop sent at the end of a session is still bringing the arm to rest.
  bool stopping() const noexcept { return stopping_.load(std::memory_order_acquire); }

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
  std::string last_arm_status() const;

 private:
  struct Outgoing {
    std::string bytes;
    Request request;
  };

  void run() noexcept;
  void serve(Clock::time_point now);
  void wait_for_io(Clock::time_point now);
  void read_tcp(Clock::time_point now);
  void handle_line(const std::string& line, Clock::time_point now);
  void read_push();
  void take_requests(Clock::time_point now);
  void flush_tcp();
  void follow_estop();
  void stream(Clock::time_point now);
  /// Every joint still (and, with `target`, within 2 mrad of it).
  bool at_rest(const ArmFeedback& measured, const JointValues* target) const;
  void poll_state(Clock::time_point now);
  /// One feedback sample from the push or a poll, in robotd's units.
  struct Sample {
    JointValues position_rad{};
    std::optional<JointValues> velocity_rad_s;  // differentiated from positions when absent
    std::array<bool, kMaxDof> enabled{};
    std::optional<driver::Pose> pose;
    std::vector<std::uint16_t> errors;
    std::array<std::uint16_t, kMaxDof> joint_errors{};
  };
  void publish(const Sample& sample, Clock::time_point now);
  void lose_link(const std::string& why);
  void wake() const { io_.wake(); }

  LinkSettings settings_;
  transport::Socket tcp_;
  transport::Socket udp_;
  transport::Endpoint push_endpoint_;
  transport::IoThread io_;

  // Between request() callers and the link thread.
  std::mutex queue_mutex_;
  std::vector<Outgoing> queue_;

  // Between the RT thread (or readers) and the link thread.
  driver::SeqLock<StreamTarget> target_;
  bool published_estop_ = false;  // RT thread only
  driver::SeqLock<ArmFeedback> feedback_;
  driver::SeqLock<LinkHealth> health_;
  driver::SeqLock<LinkCounters> counters_;
  std::atomic<bool> restart_stream_{true};
  std::atomic<bool> stopping_{false};
  mutable std::mutex status_mutex_;
  std::string arm_status_;

  // Link thread only.
  StreamTarget target_read_;  // the newest target it could read (the RT thread may be mid-store)
  ArmFeedback latest_;        // what it last published
  RequestTracker tracker_;
  LineSplitter splitter_;
  std::string tcp_out_;
  LinkCounters link_counters_;
  Clock::time_point last_feedback_at_{};  // {}: none yet
  JointValues previous_position_{};
  std::uint64_t feedback_sequence_ = 0;
  Clock::time_point next_stream_at_{};
  Clock::time_point last_stream_at_{};
  Clock::time_point next_poll_at_{};
  bool poll_in_flight_ = false;
  bool streaming_ = false;
  bool estop_sent_ = false;
  JointValues last_sent_{};
  bool lost_ = false;
};

}  // namespace robotd::realman
