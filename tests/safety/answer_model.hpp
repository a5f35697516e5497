// The checker's model of one closed-loop session's answers, written from the rule in
// docs/design.md "Closed loop" (not from the loop's AnswerBook): the session becomes closed-loop
// with the first answer the loop applies; each tick whose state the loop offered (from the one
// that answer names) is decided once, on the first tick after it: in time if the answer applied
// on that tick names it. An answer to a tick the loop never offered decides nothing.
// The success rate is the fraction in time over the last kSuccessRateWindowTicks decisions,
// judged against the session's minimum only over a full window.
#pragma once

#include <array>
#include <cstdint>

#include "robotd/messages.hpp"

namespace robotd::safety {

class AnswerModel {
 public:
  explicit AnswerModel(float min_rate = 0) : min_rate_(min_rate) {}

  /// One tick of the loop: `answer` is what the session's newest accepted command names (0 =
  /// none), `answer_offered` whether the loop offered that tick's state, `offered` the newest
  /// tick whose state the loop offered before this tick.
  void tick(std::uint64_t answer, bool answer_offered, std::uint64_t offered);

  bool closed_loop() const { return closed_loop_; }
  std::uint64_t decided() const { return decided_; }
  std::uint64_t in_time() const { return in_time_; }
  std::uint64_t in_time_in_window() const { return window_in_time_; }
  /// Below the minimum over a full window.
  bool low() const { return low_; }
  /// The rate fell below the minimum on this tick, or came back to it.
  bool fell() const { return low_ && !was_low_; }
  bool recovered() const { return !low_ && was_low_; }

 private:
  void decide(bool in_time);

  float min_rate_;
  bool closed_loop_ = false;
  std::uint64_t newest_applied_ = 0;  // the newest tick an applied answer named
  std::uint64_t newest_decided_ = 0;  // the newest offered tick decided
  std::uint64_t decided_ = 0;
  std::uint64_t in_time_ = 0;
  std::array<bool, kSuccessRateWindowTicks> window_{};  // the decisions, oldest overwritten first
  std::uint32_t window_size_ = 0;
  std::uint32_t window_in_time_ = 0;
  bool low_ = false;
  bool was_low_ = false;
};

}  // namespace robotd::safety
