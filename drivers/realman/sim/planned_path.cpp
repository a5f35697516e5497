#include "planned_path.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "robotd/kinematics/tcp_line.hpp"

namespace robotd::realman::sim {
namespace {

double speed_fraction(int speed_percent) { return std::clamp(speed_percent, 1, 100) / 100.0; }

}  // namespace

MotionProfile::MotionProfile(double cruise_s) {
  if (cruise_s <= 0) return;
  if (cruise_s >= kRampS) {  // trapezoid: reaches 1 / cruise_s
    ramp_s_ = kRampS;
    peak_speed_ = 1.0 / cruise_s;
    duration_s_ = cruise_s + kRampS;
    return;
  }
  // triangle with the trapezoid's acceleration (1 / (cruise_s · kRampS))
  const double acceleration = 1.0 / (cruise_s * kRampS);
  ramp_s_ = std::sqrt(1.0 / acceleration);
  peak_speed_ = acceleration * ramp_s_;
  duration_s_ = 2 * ramp_s_;
}

double MotionProfile::progress(double t_s) const {
  if (t_s >= duration_s_) return 1.0;
  if (t_s <= 0) return 0.0;
  const double acceleration = peak_speed_ / ramp_s_;
  if (t_s < ramp_s_) return 0.5 * acceleration * t_s * t_s;
  const double left_s = duration_s_ - t_s;
  if (left_s < ramp_s_) return 1.0 - 0.5 * acceleration * left_s * left_s;
  return 0.5 * peak_speed_ * ramp_s_ + peak_speed_ * (t_s - ramp_s_);
}

PlannedPath PlannedPath::joint_line(const JointValues& from, const JointValues& to, std::size_t dof,
                                    int speed_percent) {
  double longest_rad = 0;
  for (std::size_t j = 0; j < dof; ++j) longest_rad = std::max(longest_rad, std::abs(to[j] - from[j]));
  return PlannedPath({from, to}, longest_rad / (kMaxJointSpeedRadS * speed_fraction(speed_percent)));
}

Result<PlannedPath> PlannedPath::cartesian_line(const ArmKinematics& kinematics, const JointValues& from,
                                                const EulerPose& to, int speed_percent) {
  const kinematics::PointSolver solve = [&kinematics](const Eigen::Isometry3d& point, const JointValues& seed) {
    return kinematics.solve(point, seed);
  };
  kinematics::TcpLine line =
      kinematics::plan_tcp_line(kinematics.flange(from), isometry_of(to), from, kinematics.dof(), solve);
  const std::string where = std::to_string(static_cast<int>(line.failed_fraction * 100)) + "% of the way";
  switch (line.failure) {
    case kinematics::TcpLine::Failure::kUnreachable:
      return make_error(ErrorCode::kRefused, "0x1003 unreachable: the line leaves the workspace " + where);
    case kinematics::TcpLine::Failure::kJointJump:
      return make_error(ErrorCode::kRefused, "0x1003 unreachable: joint " + std::to_string(line.jumping_joint + 1) +
                                                 " would jump near a singularity " + where);
    case kinematics::TcpLine::Failure::kNone:
      break;
  }
  const double fraction = speed_fraction(speed_percent);
  const double cruise_s =
      std::max(line.travel_m / (kMaxLinearSpeedMS * fraction), line.turn_rad / (kMaxAngularSpeedRadS * fraction));
  return PlannedPath(std::move(line.samples), cruise_s);
}

JointValues PlannedPath::at(double t_s) const { return kinematics::joints_along(samples_, profile_.progress(t_s)); }

}  // namespace robotd::realman::sim
