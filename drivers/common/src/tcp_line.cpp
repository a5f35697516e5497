#include "robotd/kinematics/tcp_line.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::kinematics {

TcpLine plan_tcp_line(const Eigen::Isometry3d& start, const Eigen::Isometry3d& goal, const ArmJoints& from,
                      std::size_t dof, const PointSolver& solve, const LineSampling& sampling) {
  TcpLine line;
  const Eigen::Vector3d travel = goal.translation() - start.translation();
  const Eigen::Quaterniond start_rotation(start.linear());
  const Eigen::Quaterniond goal_rotation(goal.linear());
  line.travel_m = travel.norm();
  line.turn_rad = start_rotation.angularDistance(goal_rotation);
  const auto steps = static_cast<std::size_t>(
      std::max({1.0, std::ceil(line.travel_m / sampling.step_m), std::ceil(line.turn_rad / sampling.step_rad)}));

  line.samples.reserve(steps + 1);
  line.samples.push_back(from);
  for (std::size_t k = 1; k <= steps; ++k) {
    const double u = static_cast<double>(k) / static_cast<double>(steps);
    Eigen::Isometry3d point = Eigen::Isometry3d::Identity();
    point.translate(start.translation() + u * travel);
    point.rotate(start_rotation.slerp(u, goal_rotation));
    const auto joints = solve(point, line.samples.back());
    if (!joints) {
      line.failure = TcpLine::Failure::kUnreachable;
      line.failed_fraction = u;
      return line;
    }
    for (std::size_t j = 0; j < dof; ++j) {
      if (std::abs((*joints)[j] - line.samples.back()[j]) > sampling.max_joint_jump_rad) {
        line.failure = TcpLine::Failure::kJointJump;
        line.failed_fraction = u;
        line.jumping_joint = j;
        return line;
      }
    }
    line.samples.push_back(*joints);
  }
  return line;
}

ArmJoints joints_along(const std::vector<ArmJoints>& samples, double u) {
  if (samples.size() < 2) return samples.front();
  const double index = std::clamp(u, 0.0, 1.0) * static_cast<double>(samples.size() - 1);
  const auto below = std::min(static_cast<std::size_t>(index), samples.size() - 2);
  const double within = index - static_cast<double>(below);
  ArmJoints joints{};
  for (std::size_t j = 0; j < joints.size(); ++j) {
    joints[j] = samples[below][j] + within * (samples[below + 1][j] - samples[below][j]);
  }
  return joints;
}

}  // namespace robotd::kinematics
