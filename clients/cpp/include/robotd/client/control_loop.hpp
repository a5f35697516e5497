// Closed-loop control through robotd: a law called with the state each tick of the device's loop
// measured (TickState), whose answer robotd applies on the next tick.
//
//   auto report = session.run_control_loop([&](const robotd::TickState& state) {
//     robotd::Command command;
//     for (std::size_t j = 0; j < state.position.size(); ++j) {
//       command.torques.push_back(static_cast<float>(kp * (q_ref[j] - state.position[j]) - kd * state.velocity[j]));
//     }
//     return command;
//   }, {.duration = std::chrono::seconds(10)});
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>

#include "robotd/messages.hpp"

namespace robotd {

struct Command;

/// The control law: the command answering one tick's state. A Command with `finished` set is
/// sent as the loop's last answer (like libfranka's MotionFinished).
using ControlLaw = std::function<Command(const TickState&)>;

/// How Session::run_control_loop ends, besides a finished command from the law.
struct ControlLoopOptions {
  /// 0 = no limit; else the loop ends (without error) after the first tick this long after it started.
  std::chrono::milliseconds duration{0};
  /// Null, or a flag set from another thread or a signal handler: the loop checks it before each
  /// tick and ends without error when it is set.
  const std::atomic<bool>* stop = nullptr;
  /// The longest the loop waits for a tick newer than the last; then it ends with a kTimeout error
  /// (the device stopped ticking or faulted, or robotd stopped). Also the wait for the first tick.
  std::chrono::milliseconds state_timeout{200};
};

/// What a control loop saw.
struct ControlLoopReport {
  std::uint64_t ticks_seen = 0;      // states the law was called with
  std::uint64_t ticks_answered = 0;  // answers published
  /// Ticks between two states the loop saw that it never saw itself (a gap in tick numbers: the
  /// law or this process took longer than a period, or robotd published every Nth tick only).
  std::uint64_t ticks_skipped = 0;
  std::uint64_t first_tick = 0;  // the first and last tick the law was called with (0 = none)
  std::uint64_t last_tick = 0;
  bool finished = false;  // the law returned a finished command (else: duration or stop ended the loop)
};

/// Before a device's next tick, how long "send aligned" mode publishes. A command then waits in
/// robotd about the lead minus its DDS one-way time, and reaches the device about the lead plus
/// the loop's wake-up after it was sent. The one-way time on loopback is 30–150 µs (p50–p99,
/// bench/tools/bench_pingpong.cpp; docs/performance.md "Closed loop"): 120 µs makes nearly every
/// command its tick on a quiet host and keeps the median within 100 µs of the one-way time; a
/// loaded host wants more (a command that misses its tick is applied one period later).
inline constexpr std::chrono::microseconds kDefaultSendLead{120};

}  // namespace robotd
