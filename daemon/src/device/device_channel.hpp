// Everything that crosses between a device's RT loop and the rest of robotd. The RT side only
// touches lock-free structures here; the mutex below serialises the non-RT producers of
// control events among themselves and is never taken by the RT thread.
#pragma once

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>

#include "control/command_validator.hpp"
#include "control/joint_limiter.hpp"
#include "device/answer_book.hpp"
#include "robotd/driver/spsc_ring.hpp"
#include "robotd/driver/types.hpp"
#include "robotd/messages.hpp"
#include "rt/tick_signal.hpp"
#include "rt/triple_buffer.hpp"
#include "session/session_table.hpp"

namespace robotd::device {

using driver::kMaxJoints;
using session::kMaxSessionsPerDevice;

// --- command intake → RT: the newest target of every joint, and each session's last activity.

struct JointTarget {
  std::uint32_t generation = 0;  // session that wrote it (0 = none yet)
  std::uint64_t sequence = 0;    // the accepted command that wrote it: one number per command, rising
  std::int64_t received_ns = 0;  // CLOCK_MONOTONIC when robotd accepted it
  std::int64_t sent_ns = 0;      // sender's CLOCK_MONOTONIC (0 = unknown)
  control::JointTargetUpdate update;
};

struct SlotActivity {
  std::uint32_t generation = 0;
  std::int64_t last_command_ns = 0;
  std::uint64_t answers_tick = 0;  // the tick the slot's newest command answers (0 = none)
};

struct CommandSnapshot {
  std::array<JointTarget, kMaxJoints> joints{};
  std::array<SlotActivity, kMaxSessionsPerDevice> slots{};
};

// --- service side → RT: sessions starting and being released.

inline constexpr float kNoGain = std::numeric_limits<float>::quiet_NaN();

struct ControlEvent {
  enum class Type : std::uint8_t { kSessionStart, kSessionRelease };
  Type type = Type::kSessionStart;
  std::uint8_t slot = 0;
  std::uint32_t generation = 0;
  ControlMode mode = ControlMode::kPosition;
  Behavior behavior = Behavior::kKeep;  // start: applied timeout fallback; release: applied release mode
  std::int64_t timeout_ns = 0;
  std::int64_t granted_ns = 0;
  control::MotorSet motors;
  std::array<float, kMaxJoints> default_kp{};  // per joint of the device; kNoGain = use the joint default
  std::array<float, kMaxJoints> default_kd{};
  float min_success_rate = 0;  // start: closed loop, the least fraction of ticks answered in time (0 = none)
  LowRateAction on_low_success_rate = LowRateAction::kWarn;
};

// --- Device (non-RT, its limits mutex held) → RT: the device's limits after a run-time narrowing.

struct LimitSet {
  std::array<control::MotionLimits, kMaxJoints> joints{};
};

/// What the loop's limiter needs of a joint's limits.
inline control::MotionLimits motion_limits(const driver::JointLimits& limits) {
  return control::MotionLimits{limits.position_min_rad, limits.position_max_rad, limits.velocity_max_rad_s,
                               limits.acceleration_max_rad_s2};
}

// --- RT → publisher: what happened, for session bookkeeping and the log.

struct LoopEvent {
  enum class Type : std::uint8_t {
    kSessionTimedOut,
    kSessionReleased,
    kSessionEndedByShutdown,
    kSessionRateTooLow,  // ended with its fallback: its command success rate fell below its minimum
    kSuccessRateLow,     // a closed-loop session's rate fell below its minimum (it warns only)
    kSuccessRateRecovered,
    kFaultLatched,
    kEstopApplied,
    kEstopCleared,
    kBlackBoxFrozen,
  };
  Type type = Type::kFaultLatched;
  std::uint8_t slot = 0;
  std::uint32_t generation = 0;
  Behavior behavior = Behavior::kKeep;
  std::int64_t time_ns = 0;
  std::int64_t silence_ns = 0;  // timeout: time since the session's last command
  float success_rate = 0;       // the success-rate events: the rate over the window
  bool by_estop_input = false;  // e-stop applied because the device's own e-stop input is pressed
  driver::FaultInfo fault;
};

/// Whether the loop ended a session with this event (its slot and generation say which).
inline bool ends_session(LoopEvent::Type type) {
  return type == LoopEvent::Type::kSessionTimedOut || type == LoopEvent::Type::kSessionReleased ||
         type == LoopEvent::Type::kSessionEndedByShutdown || type == LoopEvent::Type::kSessionRateTooLow;
}

struct TickTiming {
  std::int64_t wake_latency_ns = 0;        // actual wake − deadline
  std::int64_t execution_ns = 0;           // wake → end of tick
  std::int64_t period_ns = 0;              // wake − previous wake
  std::int64_t answer_round_trip_ns = -1;  // a tick's deadline → robotd accepted its answer; -1 = none this tick
};

/// The loop's latest view of the device, published every tick.
struct LoopState {
  std::uint64_t tick = 0;
  std::int64_t time_ns = 0;      // the tick's wake-up
  std::int64_t deadline_ns = 0;  // the tick's deadline
  std::int64_t period_ns = 0;    // the next tick is due at deadline_ns + period_ns
  std::int64_t ready_ns = 0;     // when the loop handed this state over
  bool state_due = false;        // a state to publish (every state_every_ticks-th tick)
  DeviceState state = DeviceState::kConnecting;
  bool estop = false;
  driver::FaultInfo fault;
  bool link_lost = false;  // the fault is a lost link: robotd may reconnect on its own
  driver::Feedback feedback;
  std::uint64_t overruns = 0;
  std::int64_t rt_allocations = -1;
  bool realtime = false;
  std::array<AnswerCounts, kMaxSessionsPerDevice> answers{};  // per session slot
};

/// Black box: the last ticks in full, frozen on a fault so the moments before it survive.
struct BlackBoxJoint {
  float position_rad = 0;
  float velocity_rad_s = 0;
  float command_position_rad = 0;
  float command_torque_nm = 0;
  std::uint8_t command_kind = 0;
};
struct BlackBoxRecord {
  std::uint64_t tick = 0;
  std::int64_t time_ns = 0;
  std::int64_t wake_latency_ns = 0;
  std::int64_t execution_ns = 0;
  DeviceState state = DeviceState::kConnecting;
  std::uint8_t joint_count = 0;
  std::array<BlackBoxJoint, kMaxJoints> joints{};
};
inline constexpr std::size_t kBlackBoxTicks = 512;

struct DeviceChannel {
  rt::TripleBuffer<CommandSnapshot> commands;
  rt::TripleBuffer<LimitSet> limits;  // taken at the start of a tick
  driver::SpscRing<ControlEvent, 64> control_events;
  std::mutex control_events_producers;  // non-RT producers only

  driver::SpscRing<LoopEvent, 256> loop_events;
  driver::SpscRing<TickTiming, 16384> timings;
  rt::TripleBuffer<LoopState> state;
  // With a state every N > 1 ticks: the newest due state, so that a publisher woken late still
  // publishes it rather than a newer tick's that is not due (with N = 1 `state` is every due state).
  rt::TripleBuffer<LoopState> due_state;
  rt::TickSignal state_ready;  // RT → publisher: a new state is in `state`

  std::array<BlackBoxRecord, kBlackBoxTicks> black_box{};
  std::atomic<std::uint64_t> black_box_next{0};  // records written so far
  std::atomic<bool> black_box_freeze_requested{false};
  std::atomic<bool> black_box_frozen{false};  // RT stops writing until cleared

  std::atomic<bool> estop{false};
  std::atomic<bool> estop_input_pressed{false};   // RT → services: the device's e-stop input, now
  std::atomic<std::int64_t> estop_reached_ns{0};  // RT → services: when the first e-stop frame since the
                                                  // engagement reached the driver (CLOCK_MONOTONIC), 0 = not yet
  std::atomic<bool> maintenance_requested{false};
  std::atomic<bool> maintenance_active{false};    // RT ack: no driver I/O until cleared
  std::atomic<bool> maintenance_declined{false};  // RT: not begun, an e-stop or shutdown is pending
  std::atomic<bool> maintenance_clears_fault{false};
  std::atomic<bool> shutdown_requested{false};
  std::atomic<bool> stopped{false};

  std::atomic<std::uint64_t> ticks{0};  // liveness, for the watchdog
  std::atomic<DeviceState> device_state{DeviceState::kConnecting};
  std::atomic<std::uint64_t> dropped_stale{0};  // accepted commands whose session ended first
  std::atomic<std::uint64_t> lost_events{0};    // loop events dropped because the ring was full

  /// Queues `event` for the loop. False if the ring is full (the caller reports it).
  bool post(const ControlEvent& event) {
    const std::lock_guard lock(control_events_producers);
    return control_events.push(event);
  }
};

}  // namespace robotd::device
