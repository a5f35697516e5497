#include "driver/transaction_table.hpp"

#include <algorithm>

namespace robotd::xarm {

std::uint16_t TransactionTable::next_id() {
  last_id_ = last_id_ == 0xFFFF ? 1 : static_cast<std::uint16_t>(last_id_ + 1);
  return last_id_;
}

void TransactionTable::add(std::uint16_t id, std::uint8_t reg, Clock::time_point deadline, Callback on_reply) {
  pending_.push_back(Pending{.id = id, .reg = reg, .deadline = deadline, .on_reply = std::move(on_reply)});
}

bool TransactionTable::answer(Reply reply) {
  const auto found = std::find_if(pending_.begin(), pending_.end(),
                                  [&](const Pending& p) { return p.id == reply.transaction_id && p.reg == reply.reg; });
  if (found == pending_.end()) return false;
  Callback on_reply = std::move(found->on_reply);
  pending_.erase(found);
  on_reply(std::move(reply));
  return true;
}

std::size_t TransactionTable::expire(Clock::time_point now) {
  std::vector<Pending> overdue;
  const auto late =
      std::stable_partition(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.deadline > now; });
  std::move(late, pending_.end(), std::back_inserter(overdue));
  pending_.erase(late, pending_.end());
  for (Pending& p : overdue) {
    p.on_reply(make_error(ErrorCode::kTimeout, "no reply to " + register_name(p.reg) + " from the controller"));
  }
  return overdue.size();
}

void TransactionTable::fail_all(const std::string& why) {
  std::vector<Pending> failed;
  failed.swap(pending_);
  for (Pending& p : failed) p.on_reply(make_error(ErrorCode::kNotAvailable, register_name(p.reg) + ": " + why));
}

std::optional<Clock::time_point> TransactionTable::next_deadline() const {
  if (pending_.empty()) return std::nullopt;
  return std::min_element(pending_.begin(), pending_.end(),
                          [](const Pending& a, const Pending& b) { return a.deadline < b.deadline; })
      ->deadline;
}

std::size_t TransactionTable::in_flight(std::uint8_t reg) const {
  return static_cast<std::size_t>(
      std::count_if(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.reg == reg; }));
}

}  // namespace robotd::xarm
