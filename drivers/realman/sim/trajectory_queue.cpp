#include "trajectory_queue.hpp"

#include <algorithm>

namespace robotd::realman::sim {

JointValues TrajectoryQueue::next_start(const JointValues& position) const {
  if (!held_.empty()) return held_.back().joints;
  if (!released_.empty()) return released_.back().joints;
  if (active_) return active_->path.end();
  return position;
}

std::optional<JointValues> TrajectoryQueue::final_target() const {
  if (!released_.empty()) return released_.back().joints;
  if (active_) return active_->path.end();
  return std::nullopt;
}

void TrajectoryQueue::add(Segment segment, bool connect, const JointValues& position,
                          std::vector<TrajectoryEnd>& ends) {
  held_.push_back(std::move(segment));
  if (connect) return;
  while (!held_.empty()) {
    released_.push_back(std::move(held_.front()));
    held_.pop_front();
  }
  if (!active_ && !paused_) start_next(position, ends);
}

void TrajectoryQueue::start_next(const JointValues& position, std::vector<TrajectoryEnd>& ends) {
  if (released_.empty()) return;
  Segment segment = std::move(released_.front());
  released_.pop_front();
  auto path = planner_(segment, position);
  if (!path) {  // the arm is not where the segment was checked from, and it cannot go
    ends.push_back(TrajectoryEnd{.client = segment.client, .reached = false, .more_segments = false});
    released_.clear();
    return;
  }
  active_ = Running{.segment = std::move(segment), .path = std::move(path).value(), .time_s = 0};
}

std::optional<JointValues> TrajectoryQueue::advance(double dt_s, std::vector<TrajectoryEnd>& ends) {
  const double target_rate = paused_ || slowing_ ? 0.0 : 1.0;
  const double previous_rate = rate_;
  const double step = dt_s / kHaltRampS;
  rate_ = target_rate < rate_ ? std::max(target_rate, rate_ - step) : std::min(target_rate, rate_ + step);
  double path_dt_s = 0.5 * (previous_rate + rate_) * dt_s;

  if (slowing_ && rate_ == 0.0) {  // came to rest on the path: the trajectory is over
    std::optional<JointValues> held;
    if (active_) held = active_->path.at(active_->time_s + path_dt_s);
    abort(ends);
    return held;
  }
  while (active_) {
    active_->time_s += path_dt_s;
    if (active_->time_s < active_->path.duration_s()) return active_->path.at(active_->time_s);
    const JointValues end = active_->path.end();
    path_dt_s = active_->time_s - active_->path.duration_s();  // carried into the next segment
    ends.push_back(
        TrajectoryEnd{.client = active_->segment.client, .reached = true, .more_segments = !released_.empty()});
    active_.reset();
    if (paused_) return end;
    start_next(end, ends);
    if (!active_) return end;
  }
  return std::nullopt;
}

void TrajectoryQueue::abort(std::vector<TrajectoryEnd>& ends) {
  const Segment* first = active_              ? &active_->segment
                         : !released_.empty() ? &released_.front()
                         : !held_.empty()     ? &held_.front()
                                              : nullptr;
  if (first != nullptr)
    ends.push_back(TrajectoryEnd{.client = first->client, .reached = false, .more_segments = false});
  active_.reset();
  released_.clear();
  held_.clear();
  paused_ = false;
  slowing_ = false;
  rate_ = 1.0;
}

void TrajectoryQueue::slow_stop(std::vector<TrajectoryEnd>& ends) {
  if (!active_ || rate_ == 0.0) {
    abort(ends);
    return;
  }
  slowing_ = true;
}

void TrajectoryQueue::pause() { paused_ = true; }

void TrajectoryQueue::resume(const JointValues& position, std::vector<TrajectoryEnd>& ends) {
  if (!paused_) return;
  paused_ = false;
  if (!active_) start_next(position, ends);
}

Result<void> TrajectoryQueue::delete_current(std::vector<TrajectoryEnd>& ends) {
  if (!paused_) return make_error(ErrorCode::kRefused, "only after set_arm_pause: the arm is not paused");
  if (active_) {
    ends.push_back(
        TrajectoryEnd{.client = active_->segment.client, .reached = false, .more_segments = !released_.empty()});
    active_.reset();
  }
  if (released_.empty()) paused_ = false;  // nothing left to continue
  return {};
}

Result<void> TrajectoryQueue::delete_all(std::vector<TrajectoryEnd>& ends) {
  if (!paused_) return make_error(ErrorCode::kRefused, "only after set_arm_pause: the arm is not paused");
  abort(ends);
  return {};
}

}  // namespace robotd::realman::sim
