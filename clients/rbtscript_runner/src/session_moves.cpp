#include "robotd/motion/session_moves.hpp"

#include <string>

#include "device_lookup.hpp"
#include "robotd/rbtscript/arm_planner.hpp"

namespace robotd::motion {
namespace {

// A planner for the session's device, after checking that the session can carry its moves.
Result<rbtscript::ArmPlanner> planner_for(Client& client, const Session& session) {
  auto device = rbtscript::detail::find_device(client, session.device());
  if (!device) return device.error();
  auto planner = rbtscript::ArmPlanner::for_device(device.value());
  if (!planner) return planner.error();
  if (session.mode() != ControlMode::kPosition) {
    return Error{ErrorCode::kInvalidArgument,
                 "a planned move needs a POSITION session; this one on '" + session.device() + "' is in another mode"};
  }
  const std::vector<std::int32_t>& motors = session.motor_ids();
  const std::size_t joints = planner.value().joint_count();
  bool every_joint = motors.size() == joints;
  for (std::size_t j = 0; every_joint && j < joints; ++j) every_joint = motors[j] == static_cast<std::int32_t>(j);
  if (!every_joint) {
    return Error{ErrorCode::kInvalidArgument, "a planned move needs a session on the arm's joints of device '" +
                                                  session.device() + "', motors 0.." + std::to_string(joints - 1) +
                                                  " in order; this one holds " + std::to_string(motors.size()) +
                                                  " motor(s)"};
  }
  return planner;
}

Result<StreamReport> follow(Client& client, Session& session, const Result<Trajectory>& planned,
                            const std::atomic<bool>* stop) {
  if (!planned) return planned.error();
  auto streamer = TrajectoryStreamer::create(client, session);
  if (!streamer) return streamer.error();
  static const std::atomic<bool> kNeverStop{false};
  StreamOptions options;
  options.arrival = Arrival{kMoveArrivalToleranceRad, kMoveArrivalTimeout};
  const Trajectory& trajectory = planned.value();
  return streamer.value().stream(SampledTrajectory{trajectory.dt_s, trajectory.positions, trajectory.velocities},
                                 stop != nullptr ? *stop : kNeverStop, options);
}

}  // namespace

Result<StreamReport> move_joints(Client& client, Session& session, const std::vector<double>& target_rad,
                                 const MoveTiming& timing, const std::atomic<bool>* stop) {
  auto planner = planner_for(client, session);
  if (!planner) return planner.error();
  auto from = rbtscript::detail::measured_joints(client, planner.value().device(), planner.value().joint_count());
  if (!from) return from.error();
  return follow(client, session, planner.value().plan_joints(from.value(), target_rad, timing), stop);
}

Result<StreamReport> move_cartesian(Client& client, Session& session, const kinematics::EulerPose& goal,
                                    const MoveTiming& timing, CartesianPath path, const std::atomic<bool>* stop) {
  auto planner = planner_for(client, session);
  if (!planner) return planner.error();
  auto from = rbtscript::detail::measured_joints(client, planner.value().device(), planner.value().joint_count());
  if (!from) return from.error();
  return follow(client, session, planner.value().plan_pose(from.value(), goal, timing, path == CartesianPath::kLine),
                stop);
}

}  // namespace robotd::motion
