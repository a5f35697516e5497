#include "device_executor.hpp"

#include <utility>

#include "robotd/motion/session_moves.hpp"

namespace robotd::rbtscript::detail {

DeviceExecutor::DeviceExecutor(ArmSession& arm, const ArmPlanner& planner, const motion::DeviceIo& io,
                               const std::atomic<bool>& stop, motion::Joints start)
    : arm_(arm), planner_(planner), io_(io), stop_(stop), held_(std::move(start)) {}

Result<motion::Joints> DeviceExecutor::stream(const motion::SampledTrajectory& trajectory,
                                              const motion::StreamOptions& options) {
  auto report = arm_.streamer().stream(trajectory, stop_, options);
  if (!report) return report.error();
  if (report.value().end == motion::StreamEnd::kStopped) {
    held_ = report.value().last_measured_rad;  // the streamer holds the arm there
    return Error{ErrorCode::kRefused, "stopped: " + report.value().summary};
  }
  return std::move(report).value().last_measured_rad;
}

Result<void> DeviceExecutor::follow(const Result<PlannedMove>& move) {
  if (!move) return move.error();
  const motion::Trajectory& planned = move.value().trajectory;
  motion::StreamOptions options;
  if (move.value().tracking == Tracking::kSpeedOnly) {
    options.tracking = motion::Tracking::kSpeedOnly;  // misses its goal by design: no arrival to wait for
  } else {
    options.arrival = motion::Arrival{motion::kMoveArrivalToleranceRad, motion::kMoveArrivalTimeout};
  }
  const motion::SampledTrajectory samples{planned.dt_s, planned.positions, planned.velocities};
  auto measured = stream(samples, options);
  if (!measured) return measured.error();
  // A speed-only move ends short of its goal by design: the next move starts where it ended.
  if (options.tracking == motion::Tracking::kSpeedOnly) {
    held_ = std::move(measured).value();
  } else {
    held_ = planned.positions.back();
  }
  return {};
}

Result<void> DeviceExecutor::delay(const Delay& statement) {
  if (statement.seconds <= 0) return {};
  // Two equal samples `seconds` apart: the streamer keeps commanding the held position, which
  // keeps the session alive and watches for a stop, an e-stop or a fault all the while.
  const motion::Joints rest(held_.size(), 0.0);
  auto held = stream(motion::SampledTrajectory{statement.seconds, {held_, held_}, {rest, rest}}, {});
  if (!held) return held.error();
  return {};
}

Result<void> DeviceExecutor::call(const Result<motion::DeviceCall>& call) {
  if (!call) return call.error();
  auto done = arm_.run(io_, call.value());
  if (!done) return done.error();
  return {};
}

Result<void> DeviceExecutor::output(const Output& statement) {
  return call(io_.output(statement.number, statement.level == Level::kHigh));
}

Result<void> DeviceExecutor::gripper_calibrate(const GripperCalibrate& /*statement*/) {
  return call(io_.gripper_calibrate());
}

Result<void> DeviceExecutor::gripper(const Gripper& statement) {
  return call(io_.gripper({statement.position, statement.speed, statement.current_ma}));
}

}  // namespace robotd::rbtscript::detail
