// A straight line of a tool between two poses, solved into joint positions: how the simulators
// plan linear moves. The position moves along the line, the orientation turns about one axis
// (slerp); the joints are solved every `step_m` of travel and `step_rad` of turn, each point
// seeded with the solution before it, so that the joints stay on one branch. A planned path is
// then read back by interpolating between those samples.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "robotd/kinematics/arm_model.hpp"

namespace robotd::kinematics {

/// The joints that put the tool on `point`, searched from `seed`; nullopt when unreachable.
using PointSolver = std::function<std::optional<ArmJoints>(const Eigen::Isometry3d& point, const ArmJoints& seed)>;

struct LineSampling {
  double step_m = 1e-3;
  double step_rad = 1e-2;
  /// Between two samples no joint of a regular posture turns this far; more means the solver
  /// changed branches or the line crosses a singularity.
  double max_joint_jump_rad = 0.2;
};

struct TcpLine {
  enum class Failure { kNone, kUnreachable, kJointJump };

  /// Evenly spaced along the line, from `from` to the goal's joints (when failure is kNone).
  std::vector<ArmJoints> samples;
  double travel_m = 0;
  double turn_rad = 0;
  Failure failure = Failure::kNone;
  double failed_fraction = 0;     // how far along the line it failed (0 … 1)
  std::size_t jumping_joint = 0;  // kJointJump: which joint (from 0)
};

/// The line from `start` (where `from` puts the tool) to `goal`.
TcpLine plan_tcp_line(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal, const ArmJoints& from,
                      std::size_t dof, const PointSolver& solve, const LineSampling& sampling = {});

/// The joints a fraction `u` (0 … 1) along evenly spaced `samples` (at least one), interpolated
/// linearly between the two around it.
ArmJoints joints_along(const std::vector<ArmJoints>& samples, double u);

}  // namespace robotd::kinematics
