// Requests in flight on the command port, keyed by transaction id (the controller echoes it;
// a reply for an id nobody waits for is skipped, as both SDKs do). Link thread only.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "codec/xarm_codec.hpp"
#include "robotd/result.hpp"

namespace robotd::xarm {

using Clock = std::chrono::steady_clock;

class TransactionTable {
 public:
  using Callback = std::function<void(Result<Reply>)>;

  /// The id for the next request: 1 … 65535, then 1 again (0 is never used).
  std::uint16_t next_id();
  void add(std::uint16_t id, std::uint8_t reg, Clock::time_point deadline, Callback on_reply);
  /// Answers the request `reply` belongs to. False when none waits for it (unknown id, or a
  /// register other than the one sent — the SDKs reject that mismatch).
  bool answer(Reply reply);
  /// Fails every request whose deadline passed; returns how many.
  std::size_t expire(Clock::time_point now);
  /// Fails every request (the link is gone).
  void fail_all(const std::string& why);
  std::optional<Clock::time_point> next_deadline() const;
  std::size_t in_flight(std::uint8_t reg) const;
  std::size_t size() const { return pending_.size(); }

 private:
  struct Pending {
    std::uint16_t id = 0;
    std::uint8_t reg = 0;
    Clock::time_point deadline;
    Callback on_reply;
  };
  std::vector<Pending> pending_;
  std::uint16_t last_id_ = 0;
};

}  // namespace robotd::xarm
