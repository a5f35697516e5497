// The planners that others build on (a pose move on a joint move, a tool-frame move on a line),
// with errors that name the move the user asked for.
#pragma once

#include <string_view>

#include <Eigen/Geometry>

#include "robotd/kinematics/arm_model.hpp"
#include "robotd/motion/cartesian_move.hpp"
#include "robotd/motion/joint_move.hpp"

namespace robotd::motion::detail {

/// plan_joint_move, its errors starting "<what>: ".
Result<Trajectory> plan_joint_move_as(std::string_view what, const Joints& from, const Joints& to,
                                      const MoveTiming& timing, const JointLimits& limits, double dt_s);

/// plan_line_move, its errors starting "<what>: ".
Result<Trajectory> plan_line_move_as(std::string_view what, const kinematics::ArmModel& model, const Joints& from,
                                     const Eigen::Isometry3d& goal, const MoveTiming& timing, const JointLimits& limits,
                                     double dt_s, const LineOptions& options);

}  // namespace robotd::motion::detail
