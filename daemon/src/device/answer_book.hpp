// One closed-loop session's answers, kept by the RT loop (no allocation, no locks). A session
// becomes closed-loop with its first command that names a tick (ControlCommand.answers_tick).
// From then on every tick whose state the loop offered is decided once: answered in time (the
// answer was applied no later than the tick at which the next state is offered) or not; an answer
// that comes after that is counted late as well. The success rate is libfranka's
// control_command_success_rate: the fraction in time over the last kSuccessRateWindowTicks.
#pragma once

#include <array>
#include <cstdint>

#include "robotd/messages.hpp"

namespace robotd::device {

/// What the loop publishes of a session slot's answers (LoopState).
struct AnswerCounts {
  std::uint32_t generation = 0;  // the session these belong to
  bool closed_loop = false;
  std::uint64_t to_answer = 0;  // ticks decided so far
  std::uint64_t in_time = 0;
  std::uint64_t late = 0;        // decided as not in time, then applied on a later tick
  std::uint64_t unanswered = 0;  // decided as not in time and never applied (so far)
  float success_rate = 0;        // in time / decided, over the window
  bool rate_low = false;         // below the session's minimum, over a full window
};

class AnswerBook {
 public:
  /// A new session in the slot: nothing answered yet.
  void start(std::uint32_t generation, float min_success_rate) noexcept;

  /// The session's newest command answers tick `answered` (0 = none). `offered` is the newest tick
  /// whose state the loop offered before this tick; `answered_was_offered` whether the loop offered
  /// the answered tick's state (a state of an e-stopped or faulted device is published, not offered).
  /// Returns true if this was a new answer.
  bool take_answer(std::uint64_t answered, std::uint64_t offered, bool answered_was_offered) noexcept;
  /// Decides the offered tick as unanswered if its answer is due by now: `now` is this tick and a
  /// state is offered every `every` ticks.
  void close_overdue(std::uint64_t offered, std::uint64_t now, std::uint64_t every) noexcept;

  const AnswerCounts& counts() const noexcept { return counts_; }
  /// The rate has just fallen below the minimum (true once per fall).
  bool fell_below_minimum() const noexcept { return counts_.rate_low && !was_low_; }
  /// The rate has just come back to the minimum (true once per recovery).
  bool recovered() const noexcept { return !counts_.rate_low && was_low_; }
  /// Call once per tick after the checks above.
  void end_tick() noexcept { was_low_ = counts_.rate_low; }

 private:
  void decide(bool in_time) noexcept;

  AnswerCounts counts_{};
  float min_success_rate_ = 0;
  std::uint64_t newest_answer_ = 0;    // the newest tick an applied answer named
  std::uint64_t decided_through_ = 0;  // every offered tick up to this one is decided
  std::array<bool, kSuccessRateWindowTicks> window_{};
  std::uint32_t window_next_ = 0;
  std::uint32_t window_filled_ = 0;
  std::uint32_t window_in_time_ = 0;
  bool was_low_ = false;
};

}  // namespace robotd::device
