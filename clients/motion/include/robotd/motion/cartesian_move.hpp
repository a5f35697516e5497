// Moves to a pose, on the arm models of robotd/kinematics/arm_model.hpp (any joint count):
//   - plan_pose_move (RBTscript MovePose): the joints that reach the goal pose (IK seeded from
//     the start), then a joint move by the RBTscript rules (joint_move.hpp). The tool's path in
//     between is not a line.
//   - plan_line_move (MoveCart): the tool on a straight line, its orientation turning about one
//     axis (slerp), both on one s(t): with t, the commander's profile over t ("poly" unless told
//     "trap", as for joint moves); without, a thirds trapezoid (or the polynomial if told) whose
//     cruise keeps to a tool speed and turning speed. IK at every sample, seeded with the one
//     before, so that the arm stays on one branch. The line stops, with an error naming how far
//     along it, before a sample that has no solution within the joint limits, one that comes
//     close to a singularity (the Jacobian's smallest singular value below a threshold and below
//     half its value at the start: a line may start at a singularity and leave it), or one that
//     would turn a joint faster than its maximum (the error says when a singularity is why).
//   - plan_tool_relative_move (MoveCartRelTRF): the line to the start pose moved by `delta` in
//     the tool's own frame (start · delta).
// A pose is the tool's (ArmModel::tool) in the base frame, lengths in m.
#pragma once

#include <numbers>

#include <Eigen/Geometry>

#include "robotd/kinematics/arm_model.hpp"
#include "robotd/motion/joint_move.hpp"
#include "robotd/motion/trajectory.hpp"
#include "robotd/result.hpp"

namespace robotd::motion {

/// Without t, a line's tool speed: the PAROL6 driver's move_cart default (the commander's
/// Cartesian moves run at 2–60 mm/s).
inline constexpr double kDefaultLinearSpeedMS = 0.05;
/// Without t, the fastest a line turns the tool: the commander's Cartesian angular maximum, 25°/s.
inline constexpr double kDefaultAngularSpeedRadS = 25.0 * std::numbers::pi / 180.0;
/// A sample whose Jacobian's smallest singular value is below this (and below half the start's) is
/// too close to a singularity.
inline constexpr double kDefaultMinSingularValue = 1e-3;

struct LineOptions {
  double linear_speed_m_s = kDefaultLinearSpeedMS;        // without t: the tool's cruise speed
  double angular_speed_rad_s = kDefaultAngularSpeedRadS;  // without t: its fastest turn
  double min_singular_value = kDefaultMinSingularValue;   // a singularity's margin (m and rad mixed)
};

/// IK of `goal` from `from`, then a joint move; `limits` (the device's) bound the IK too.
Result<Trajectory> plan_pose_move(const kinematics::ArmModel& model, const Joints& from, const Eigen::Isometry3d& goal,
                                  const MoveTiming& timing, const JointLimits& limits, double dt_s);

/// The straight line from where `from` puts the tool to `goal`. `timing`'s v and a do not apply
/// (RBTscript's MoveCart has none).
Result<Trajectory> plan_line_move(const kinematics::ArmModel& model, const Joints& from, const Eigen::Isometry3d& goal,
                                  const MoveTiming& timing, const JointLimits& limits, double dt_s,
                                  const LineOptions& options = {});

/// The straight line to tool_pose(from) · delta: `delta` is a move in the tool's frame.
Result<Trajectory> plan_tool_relative_move(const kinematics::ArmModel& model, const Joints& from,
                                           const Eigen::Isometry3d& delta, const MoveTiming& timing,
                                           const JointLimits& limits, double dt_s, const LineOptions& options = {});

}  // namespace robotd::motion
