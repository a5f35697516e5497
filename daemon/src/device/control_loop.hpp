// One device's real-time loop. Each tick (docs/design.md "One tick"):
//   narrowed limits → maintenance handshake → driver.read → control events → e-stop / shutdown → newest
//   targets → session timeouts → closed-loop answers → safe state / limits / rate limiting →
//   driver.write → state (and a wake-up for its publisher), timing and black box out.
// The safety invariants it keeps on every tick are listed in docs/safety.md.
// Runs on the device's RT thread: no allocation, no locks, no DDS, no logging. Everything it
// says goes out through DeviceChannel.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

#include "control/device_model.hpp"
#include "control/joint_control.hpp"
#include "device/device_channel.hpp"
#include "robotd/driver/driver.hpp"

namespace robotd::device {

/// robotd's own fault codes (driver codes are the vendor's, >= 0 by convention).
inline constexpr std::int32_t kFaultNoFeedback = -1;
inline constexpr std::int32_t kFaultLinkLost = -2;
inline constexpr std::int32_t kFaultNonFiniteFeedback = -3;

struct LoopSettings {
  double rate_hz = 1000;
  std::int64_t feedback_timeout_ns = 100'000'000;
  Behavior safe_behavior = Behavior::kDamping;      // on e-stop and fault (already mapped)
  Behavior shutdown_behavior = Behavior::kDamping;  // on SIGTERM (already mapped)
  std::int64_t shutdown_duration_ns = 300'000'000;  // how long the safe stop runs before disconnect
  std::uint64_t warmup_ticks = 500;                 // allocation counting starts after these
  std::uint64_t state_every_ticks = 1;              // a state is offered to closed-loop sessions every N ticks
  bool realtime = false;                            // SCHED_FIFO was granted (reported only)
};

class ControlLoop {
 public:
  ControlLoop(driver::Driver& driver, const control::DeviceModel& model, DeviceChannel& channel,
              const LoopSettings& settings);

  /// Ticks at rate_hz on absolute deadlines until the shutdown stop has completed.
  void run() noexcept;
  /// One tick at `now_ns` for the tick due at `deadline_ns`. Exposed so tests can drive the
  /// loop deterministically without a thread.
  void tick(std::int64_t deadline_ns, std::int64_t now_ns) noexcept;
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }
  std::uint64_t overruns() const noexcept { return overruns_; }

 private:
  struct JointOwner {
    std::int8_t slot = -1;
    std::uint32_t generation = 0;
    std::uint64_t applied_sequence = 0;
    double previous_target = 0;
    std::int64_t previous_target_time_ns = 0;
  };
  struct SlotRuntime {
    bool active = false;
    std::uint32_t generation = 0;
    ControlMode mode = ControlMode::kPosition;
    Behavior timeout_behavior = Behavior::kKeep;
    std::int64_t timeout_ns = 0;
    std::int64_t granted_ns = 0;
    control::MotorSet motors;
    std::array<float, kMaxJoints> default_kp{};
    std::array<float, kMaxJoints> default_kd{};
    LowRateAction on_low_success_rate = LowRateAction::kWarn;
  };

  void take_limits() noexcept;
  void drain_control_events(std::int64_t now_ns) noexcept;
  void handle_maintenance(std::int64_t now_ns) noexcept;
  void read_feedback(std::int64_t now_ns) noexcept;
  void take_feedback(std::int64_t now_ns) noexcept;
  void take_commands() noexcept;
  void expire_sessions(std::int64_t now_ns) noexcept;
  void book_answers(std::int64_t now_ns) noexcept;
  void apply_targets() noexcept;
  void drop_stale(JointOwner& owner, const JointTarget& target) noexcept;
  void apply_target(std::size_t joint, const JointTarget& target, const SlotRuntime& slot) noexcept;
  void end_session(std::size_t slot, Behavior behavior, LoopEvent::Type why, std::int64_t now_ns,
                   std::int64_t silence_ns) noexcept;
  void set_behavior(std::size_t joint, Behavior behavior, control::Gains gains) noexcept;
  void update_estop(std::int64_t now_ns) noexcept;
  void update_shutdown(std::int64_t now_ns) noexcept;
  void enter_safe_state() noexcept;
  void leave_safe_state_if_clear(std::int64_t now_ns) noexcept;
  void latch_fault(const driver::FaultInfo& fault, std::int64_t now_ns, bool link_lost = false) noexcept;
  void latch_io_fault(driver::IoResult result, std::int64_t now_ns) noexcept;
  void write_command(std::int64_t deadline_ns, std::int64_t now_ns) noexcept;
  void publish(std::int64_t deadline_ns, std::int64_t now_ns) noexcept;
  void record_black_box(std::int64_t now_ns, std::int64_t wake_latency_ns) noexcept;
  void post(const LoopEvent& event) noexcept;
  control::Gains gains_for(std::size_t joint, const SlotRuntime* slot) const noexcept;
  DeviceState current_state() const noexcept;

  driver::Driver& driver_;
  const control::DeviceModel& model_;
  DeviceChannel& channel_;
  LoopSettings settings_;
  std::size_t joint_count_;
  std::int64_t period_ns_;
  double dt_s_;

  std::array<control::JointControl, kMaxJoints> joints_{};
  std::array<control::JointMode, kMaxJoints> saved_modes_{};  // what to resume after the safe state
  std::array<double, kMaxJoints> saved_kd_{};                 // the damping gain to resume with
  std::array<std::int64_t, kMaxJoints> last_finite_ns_{};     // the joint's last finite position and velocity
  std::array<bool, kMaxJoints> measured_{};                   // a finite reading has arrived since the link came up
  std::array<JointOwner, kMaxJoints> owners_{};
  std::array<SlotRuntime, kMaxSessionsPerDevice> slots_{};
  std::array<control::MotionLimits, kMaxJoints> motion_limits_{};
  std::array<AnswerBook, kMaxSessionsPerDevice> answers_{};
  // The last ticks, by tick number modulo their count: when each was due (an answer's round trip
  // is measured from it) and whether its state was offered for answering.
  struct RecentTick {
    std::int64_t deadline_ns = 0;
    bool offered = false;
  };
  std::array<RecentTick, 64> recent_ticks_{};
  std::uint64_t offered_tick_ = 0;          // the newest tick whose state was offered for answering
  std::int64_t answer_round_trip_ns_ = -1;  // this tick's, for TickTiming

  driver::Feedback feedback_{};
  driver::Feedback read_buffer_{};
  driver::FaultInfo io_fault_{};
  driver::FaultInfo fault_{};
  driver::CommandFrame frame_{};
  const CommandSnapshot* commands_ = nullptr;
  std::uint32_t newest_started_generation_ = 0;
  std::uint64_t last_dropped_sequence_ = 0;  // the last command counted as dropped
  std::int64_t stale_before_ns_ = 0;         // targets received before this (a safe state's end) are stale

  bool have_feedback_ = false;
  std::int64_t last_feedback_ns_ = 0;
  bool fault_latched_ = false;
  bool link_lost_ = false;  // the latched fault is a lost link (the driver said kDisconnected)
  bool estop_applied_ = false;
  bool safe_state_ = false;
  bool in_maintenance_ = false;
  bool reinit_pending_ = false;  // maintenance ended; waiting for every joint to be measured again
  bool shutdown_requested_ = false;
  bool shutting_down_ = false;  // the shutdown stop is running (not before maintenance has let go)
  std::int64_t shutdown_started_ns_ = 0;
  std::atomic<bool> finished_{false};  // read by whoever waits for the loop's end (Device::running)
  std::int64_t newest_sent_ns_ = 0;

  std::uint64_t tick_count_ = 0;
  std::uint64_t overruns_ = 0;
  std::int64_t last_execution_ns_ = 0;
  std::int64_t allocation_baseline_ = -1;
  std::int64_t rt_allocations_ = -1;
};

}  // namespace robotd::device
