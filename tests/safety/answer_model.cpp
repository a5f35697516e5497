#include "answer_model.hpp"

namespace robotd::safety {

void AnswerModel::tick(std::uint64_t answer, bool answer_offered, std::uint64_t offered) {
  was_low_ = low_;
  // An answer is applied once, when the loop has offered the tick it names; a repeat of it (the
  // mailbox holds the newest command until the next) or an older one counts for nothing.
  const bool applied = answer != 0 && answer > newest_applied_ && answer <= offered;
  if (applied) newest_applied_ = answer;
  if (!closed_loop_) {
    if (!applied) return;
    // The record starts with the tick the first answer names: in time only if it is the newest
    // offered one; an older one was late.
    closed_loop_ = true;
    newest_decided_ = answer;
    if (answer_offered) decide(answer == offered);
  } else if (applied && answer == offered && offered > newest_decided_) {
    decide(true);
    newest_decided_ = offered;
  }
  // The newest offered tick is due now: not answered on this tick, it was not answered in time.
  if (offered > newest_decided_) {
    decide(false);
    newest_decided_ = offered;
  }
}

void AnswerModel::decide(bool in_time) {
  ++decided_;
  if (in_time) ++in_time_;
  bool& oldest = window_[decided_ % window_.size()];
  if (window_size_ == window_.size()) {
    if (oldest) --window_in_time_;
  } else {
    ++window_size_;
  }
  oldest = in_time;
  if (in_time) ++window_in_time_;
  // The loop publishes the rate as a float (SessionInfo.command_success_rate) and compares that.
  const float rate = static_cast<float>(window_in_time_) / static_cast<float>(window_.size());
  low_ = min_rate_ > 0 && window_size_ == window_.size() && rate < min_rate_;
}

}  // namespace robotd::safety
