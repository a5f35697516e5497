// MovePose (IK, then a joint move) and MoveCartRelTRF (a line to the pose moved in the tool frame).
#include <string>

#include "arm_joints.hpp"
#include "describe.hpp"
#include "move_checks.hpp"
#include "named_planners.hpp"
#include "robotd/motion/cartesian_move.hpp"

namespace robotd::motion {

Result<Trajectory> plan_pose_move(const kinematics::ArmModel& model, const Joints& from, const Eigen::Isometry3d& goal,
                                  const MoveTiming& timing, const JointLimits& limits, double dt_s) {
  auto problem = detail::model_problem(model, from, limits);
  if (!problem && !goal.matrix().allFinite()) problem = "the goal pose must be finite";
  if (problem) return Error{ErrorCode::kInvalidArgument, "pose move: " + *problem};
  const kinematics::IkSolution solution = kinematics::inverse_kinematics(
      model, goal, detail::to_arm(from), detail::to_arm(limits.min_rad), detail::to_arm(limits.max_rad));
  if (!solution.converged) {
    return Error{ErrorCode::kInvalidArgument,
                 "pose move: no joint solution within the joint limits reaches the goal pose (the closest is " +
                     detail::fixed(1e3 * solution.position_error_m) + " mm and " +
                     detail::fixed(detail::degrees(solution.orientation_error_rad)) + "° off)"};
  }
  Result<Trajectory> planned =
      detail::plan_joint_move_as("pose move", from, detail::to_joints(solution.q_rad, model.dof), timing, limits, dt_s);
  if (planned) planned.value().how = "IK, then " + planned.value().how;
  return planned;
}

Result<Trajectory> plan_tool_relative_move(const kinematics::ArmModel& model, const Joints& from,
                                           const Eigen::Isometry3d& delta, const MoveTiming& timing,
                                           const JointLimits& limits, double dt_s, const LineOptions& options) {
  constexpr const char* kWhat = "tool-frame move";
  if (auto problem = detail::model_problem(model, from, limits))
    return Error{ErrorCode::kInvalidArgument, std::string(kWhat) + ": " + *problem};
  const Eigen::Isometry3d goal = kinematics::tool_pose(model, detail::to_arm(from)) * delta;
  return detail::plan_line_move_as(kWhat, model, from, goal, timing, limits, dt_s, options);
}

}  // namespace robotd::motion
