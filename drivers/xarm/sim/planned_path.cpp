#include "planned_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "robotd/kinematics/tcp_line.hpp"

namespace robotd::xarm::sim {
namespace {

/// The controller's speed scale for turns: 1 m/s of TCP speed is π rad/s of turn (§7).
constexpr double kTurnMetresPerRad = 1.0 / std::numbers::pi;

}  // namespace

PlannedPath PlannedPath::joint_line(const JointValues& from, const JointValues& to, std::size_t dof) {
  double longest_rad = 0;
  for (std::size_t j = 0; j < dof; ++j) longest_rad = std::max(longest_rad, std::abs(to[j] - from[j]));
  return PlannedPath({from, to}, longest_rad);
}

Result<PlannedPath> PlannedPath::tcp_line(const ArmKinematics& kinematics, const Eigen::Isometry3d& tcp_offset,
                                          const JointValues& from, const Eigen::Isometry3d& to) {
  const kinematics::PointSolver solve = [&kinematics, &tcp_offset](const Eigen::Isometry3d& point,
                                                                   const JointValues& seed) {
    return kinematics.solve(point, tcp_offset, seed);
  };
  kinematics::TcpLine line =
      kinematics::plan_tcp_line(kinematics.tcp(from, tcp_offset), to, from, kinematics.dof(), solve);
  const std::string where = std::to_string(static_cast<int>(line.failed_fraction * 100)) + "% of the way";
  switch (line.failure) {
    case kinematics::TcpLine::Failure::kUnreachable:
      return make_error(ErrorCode::kRefused, "no joint solution " + where);
    case kinematics::TcpLine::Failure::kJointJump:
      return make_error(ErrorCode::kRefused,
                        "joint " + std::to_string(line.jumping_joint + 1) + " would jump near a singularity " + where);
    case kinematics::TcpLine::Failure::kNone:
      break;
  }
  return PlannedPath(std::move(line.samples), std::max(line.travel_m, line.turn_rad * kTurnMetresPerRad));
}

JointValues PlannedPath::at(double s) const {
  return kinematics::joints_along(samples_, length_ > 0 ? s / length_ : 1.0);
}

JointValues PlannedPath::velocity(double s, double speed) const {
  JointValues velocity{};
  if (samples_.size() < 2 || length_ <= 0) return velocity;
  const auto segments = static_cast<double>(samples_.size() - 1);
  const auto below =
      std::min(static_cast<std::size_t>(std::clamp(s / length_, 0.0, 1.0) * segments), samples_.size() - 2);
  const double segments_per_unit = segments / length_;
  for (std::size_t j = 0; j < velocity.size(); ++j) {
    velocity[j] = (samples_[below + 1][j] - samples_[below][j]) * segments_per_unit * speed;
  }
  return velocity;
}

}  // namespace robotd::xarm::sim
