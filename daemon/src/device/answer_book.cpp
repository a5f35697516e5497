#include "device/answer_book.hpp"

#include <algorithm>

namespace robotd::device {

void AnswerBook::start(std::uint32_t generation, float min_success_rate) noexcept {
  *this = AnswerBook{};
  counts_.generation = generation;
  min_success_rate_ = min_success_rate;
}

bool AnswerBook::take_answer(std::uint64_t answered, std::uint64_t offered, bool answered_was_offered) noexcept {
  // Repeats of an answer already taken (the mailbox keeps the newest command until the next)
  // and answers to ticks the loop never offered count for nothing.
  if (answered == 0 || answered <= newest_answer_ || answered > offered) return false;
  if (!counts_.closed_loop) {
    counts_.closed_loop = true;
    decided_through_ = answered - 1;  // the session's record starts with the first tick it answered
  }
  newest_answer_ = answered;
  if (!answered_was_offered) {  // nothing to decide: that tick was never the session's to answer
    decided_through_ = std::max(decided_through_, answered);
    return true;
  }
  if (answered > decided_through_) {
    // Undecided: in time if it answers the newest state; an older one (only the first answer can
    // be) was late.
    const bool in_time = answered == offered;
    decide(in_time);
    if (!in_time) {
      --counts_.unanswered;
      ++counts_.late;
    }
    decided_through_ = answered;
  } else if (counts_.unanswered > 0) {
    --counts_.unanswered;  // decided as not in time, applied now
    ++counts_.late;
  }
  return true;
}

void AnswerBook::close_overdue(std::uint64_t offered, std::uint64_t now, std::uint64_t every) noexcept {
  if (!counts_.closed_loop || offered <= decided_through_ || now < offered + every) return;
  decide(false);
  decided_through_ = offered;
}

void AnswerBook::decide(bool in_time) noexcept {
  ++counts_.to_answer;
  if (in_time) {
    ++counts_.in_time;
  } else {
    ++counts_.unanswered;
  }
  bool& slot = window_[window_next_];
  if (window_filled_ == window_.size()) {
    window_in_time_ -= slot ? 1 : 0;
  } else {
    ++window_filled_;
  }
  slot = in_time;
  window_in_time_ += in_time ? 1 : 0;
  window_next_ = (window_next_ + 1) % static_cast<std::uint32_t>(window_.size());
  counts_.success_rate = static_cast<float>(window_in_time_) / static_cast<float>(window_filled_);
  // Judged only over a full window: the first few ticks of a loop say little about its rate.
  counts_.rate_low =
      min_success_rate_ > 0 && window_filled_ == window_.size() && counts_.success_rate < min_success_rate_;
}

}  // namespace robotd::device
