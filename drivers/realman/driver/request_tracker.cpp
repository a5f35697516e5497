#include "driver/request_tracker.hpp"

#include <algorithm>

namespace robotd::realman {
namespace {

std::string milliseconds_text(std::chrono::milliseconds duration) { return std::to_string(duration.count()) + " ms"; }

}  // namespace

void RequestTracker::sent(Request request, Clock::time_point now) {
  if (!request.shape.has_reply) {
    request.on_reply(nlohmann::json::object());
    return;
  }
  request.deadline = now + request.reply_timeout;
  awaiting_reply_.push_back(std::move(request));
}

bool RequestTracker::on_reply(const Message& reply, Clock::time_point now) {
  const auto answered = std::find_if(awaiting_reply_.begin(), awaiting_reply_.end(), [&](const Request& request) {
    return std::find(request.shape.keys.begin(), request.shape.keys.end(), reply.key) != request.shape.keys.end();
  });
  if (answered == awaiting_reply_.end()) return false;
  Request request = std::move(*answered);
  awaiting_reply_.erase(answered);
  Result<void> success;
  if (!request.shape.result_field.empty()) success = reply_success(reply, request.shape, request.command);
  if (!success) {
    request.on_reply(success.error());
    return true;
  }
  request.on_reply(reply.body);
  if (request.completion) {
    request.deadline = now + request.completion_timeout;
    awaiting_completion_.push_back(std::move(request));
  }
  return true;
}

bool RequestTracker::on_event(const TrajectoryEvent& event) {
  const auto completed = std::find_if(awaiting_completion_.begin(), awaiting_completion_.end(),
                                      [&](const Request& request) { return request.completion == event.device; });
  if (completed == awaiting_completion_.end()) return false;
  // A connected trajectory reports each segment; the request ends with the last one.
  if (event.more_segments && event.reached) return true;
  Request request = std::move(*completed);
  awaiting_completion_.erase(completed);
  if (event.reached) {
    request.on_completion(event);
  } else {
    request.on_completion(make_error(ErrorCode::kRefused, "the controller reports that " + request.command +
                                                              " did not reach its target (stopped or failed)"));
  }
  return true;
}

void RequestTracker::expire(Clock::time_point now) {
  for (auto it = awaiting_reply_.begin(); it != awaiting_reply_.end();) {
    if (now < it->deadline) {
      ++it;
      continue;
    }
    Request request = std::move(*it);
    it = awaiting_reply_.erase(it);
    request.on_reply(make_error(ErrorCode::kTimeout, "no reply to " + request.command + " from the controller within " +
                                                         milliseconds_text(request.reply_timeout)));
  }
  for (auto it = awaiting_completion_.begin(); it != awaiting_completion_.end();) {
    if (now < it->deadline) {
      ++it;
      continue;
    }
    Request request = std::move(*it);
    it = awaiting_completion_.erase(it);
    request.on_completion(make_error(ErrorCode::kTimeout, request.command +
                                                              " was accepted but did not complete within " +
                                                              milliseconds_text(request.completion_timeout)));
  }
}

void RequestTracker::fail_all(const std::string& why) {
  for (Request& request : awaiting_reply_) request.on_reply(make_error(ErrorCode::kNotAvailable, why));
  for (Request& request : awaiting_completion_) request.on_completion(make_error(ErrorCode::kNotAvailable, why));
  awaiting_reply_.clear();
  awaiting_completion_.clear();
}

std::optional<Clock::time_point> RequestTracker::next_deadline() const {
  std::optional<Clock::time_point> nearest;
  for (const auto* queue : {&awaiting_reply_, &awaiting_completion_}) {
    for (const Request& request : *queue) {
      if (!nearest || request.deadline < *nearest) nearest = request.deadline;
    }
  }
  return nearest;
}

}  // namespace robotd::realman
