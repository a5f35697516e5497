// Planned motions (spec §3.1, §3.2, §3.5): segments sent with trajectory_connect 1 wait until one
// with 0 releases them all; released segments run one after another, each planned from where the
// arm is when it starts; each end is reported (reached, or aborted). Pause, continue and slow stop
// scale the path's time: its clock slows to a halt (or back to full speed) over kHaltRampS, so
// the arm decelerates on its path.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "codec/realman_codec.hpp"
#include "planned_path.hpp"
#include "robotd/result.hpp"

namespace robotd::realman::sim {

using ClientId = std::uint64_t;

struct Segment {
  std::string type;               // what get_arm_current_trajectory reports: "movej", "movej_p", "movel"
  JointValues joints{};           // movej, movej_p: the joint target
  std::optional<EulerPose> pose;  // movel: the flange target; movej_p: the pose it was solved for
  int speed_percent = 20;
  ClientId client = 0;  // who is told when it ends
};

/// A segment ended: the current_trajectory_state event its client gets.
struct TrajectoryEnd {
  ClientId client = 0;
  bool reached = false;
  bool more_segments = false;  // trajectory_connect 1: released segments follow
};

class TrajectoryQueue {
 public:
  static constexpr double kHaltRampS = 0.2;
  /// Plans a segment from the joints it starts at (kRefused with the reason when it cannot).
  using Planner = std::function<Result<PlannedPath>(const Segment&, const JointValues& from)>;

  explicit TrajectoryQueue(Planner planner) : planner_(std::move(planner)) {}

  /// A segment runs, is paused, or waits to run: new planned motions are refused meanwhile.
  bool busy() const { return active_.has_value() || !released_.empty(); }
  const Segment* active() const { return active_ ? &active_->segment : nullptr; }
  std::size_t released() const { return released_.size(); }
  std::size_t held() const { return held_.size(); }
  bool paused() const { return paused_; }
  bool slowing() const { return slowing_; }
  /// Where a segment added now would start: the target of the last one held, else `position`.
  JointValues next_start(const JointValues& position) const;
  /// The joint target of the motion in progress (the last released segment's), if any.
  std::optional<JointValues> final_target() const;

  /// Adds a checked segment: held if `connect`, else released with all held ones and started
  /// (from `position`) unless paused.
  void add(Segment segment, bool connect, const JointValues& position, std::vector<TrajectoryEnd>& ends);
  /// Runs the path clock for `dt_s`; the joints on the path, or nullopt when no segment runs.
  std::optional<JointValues> advance(double dt_s, std::vector<TrajectoryEnd>& ends);

  /// Drops everything at once; one aborted end if anything was pending.
  void abort(std::vector<TrajectoryEnd>& ends);
  void slow_stop(std::vector<TrajectoryEnd>& ends);
  void pause();
  void resume(const JointValues& position, std::vector<TrajectoryEnd>& ends);
  /// Only while paused (kRefused otherwise): drops the segment in progress / every segment.
  Result<void> delete_current(std::vector<TrajectoryEnd>& ends);
  Result<void> delete_all(std::vector<TrajectoryEnd>& ends);

 private:
  struct Running {
    Segment segment;
    PlannedPath path;
    double time_s = 0;
  };

  void start_next(const JointValues& position, std::vector<TrajectoryEnd>& ends);

  Planner planner_;
  std::deque<Segment> held_;      // trajectory_connect 1, waiting for a 0
  std::deque<Segment> released_;  // to run after the active one
  std::optional<Running> active_;
  double rate_ = 1.0;  // path seconds per second
  bool paused_ = false;
  bool slowing_ = false;
};

}  // namespace robotd::realman::sim
