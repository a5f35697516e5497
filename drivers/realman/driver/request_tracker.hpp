// Requests in flight on the controller's TCP connection. Replies carry no request id, so a reply
// answers the oldest request waiting for its key ("command" or "state" value), and a
// current_trajectory_state event completes the oldest request waiting on that device. Used by
// the link thread only.
#pragma once

#include <chrono>
#include <deque>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "codec/realman_codec.hpp"
#include "robotd/result.hpp"

namespace robotd::realman {

using Clock = std::chrono::steady_clock;

struct Request {
  std::string command;
  ReplyShape shape;
  std::chrono::milliseconds reply_timeout{1000};
  /// Wait, after a successful reply, for the completion event of this device.
  std::optional<Device> completion;
  std::chrono::milliseconds completion_timeout{60'000};  // from the reply on
  Clock::time_point deadline;                            // set by the tracker
  std::function<void(Result<nlohmann::json>)> on_reply;
  std::function<void(Result<TrajectoryEvent>)> on_completion;  // when `completion` is set
};

class RequestTracker {
 public:
  /// A request just sent. Without a reply (shape.has_reply false) it is answered at once.
  void sent(Request request, Clock::time_point now);
  /// True when the reply answered a request.
  bool on_reply(const Message& reply, Clock::time_point now);
  /// True when the event completed a request.
  bool on_event(const TrajectoryEvent& event);
  /// Fails every request whose reply or completion is overdue.
  void expire(Clock::time_point now);
  /// Fails every request (the link is gone).
  void fail_all(const std::string& why);
  /// The nearest deadline, if any request is waiting.
  std::optional<Clock::time_point> next_deadline() const;

 private:
  std::deque<Request> awaiting_reply_;
  std::deque<Request> awaiting_completion_;
};

}  // namespace robotd::realman
