#include "planned_path.hpp"

#include <algorithm>
#include <cmath>

namespace robotd::realman::sim {
namespace {

constexpr double kSampleStepM = 1e-3;
constexpr double kSampleStepRad = 1e-2;
/// Between two samples 1 mm apart no joint of a regular posture turns this far; more means the
/// solver changed branches or the line crosses a singularity.
constexpr double kMaxJointJumpRad = 0.2;

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
  const Eigen::Isometry3d start = kinematics.flange(from);
  const Eigen::Isometry3d goal = isometry_of(to);
  const Eigen::Vector3d travel = goal.translation() - start.translation();
  const Eigen::Quaterniond start_rotation(start.linear());
  const Eigen::Quaterniond goal_rotation(goal.linear());
  const double turn_rad = start_rotation.angularDistance(goal_rotation);
  const auto steps = static_cast<std::size_t>(
      std::max({1.0, std::ceil(travel.norm() / kSampleStepM), std::ceil(turn_rad / kSampleStepRad)}));

  std::vector<JointValues> samples{from};
  samples.reserve(steps + 1);
  for (std::size_t k = 1; k <= steps; ++k) {
    const double u = static_cast<double>(k) / static_cast<double>(steps);
    Eigen::Isometry3d point = Eigen::Isometry3d::Identity();
    point.translate(start.translation() + u * travel);
    point.rotate(start_rotation.slerp(u, goal_rotation));
    const auto joints = kinematics.solve(point, samples.back());
    if (!joints) {
      return make_error(ErrorCode::kRefused, "0x1003 unreachable: the line leaves the workspace " +
                                                 std::to_string(static_cast<int>(u * 100)) + "% of the way");
    }
    for (std::size_t j = 0; j < kinematics.dof(); ++j) {
      if (std::abs((*joints)[j] - samples.back()[j]) > kMaxJointJumpRad) {
        return make_error(ErrorCode::kRefused, "0x1003 unreachable: joint " + std::to_string(j + 1) +
                                                   " would jump near a singularity " +
                                                   std::to_string(static_cast<int>(u * 100)) + "% of the way");
      }
    }
    samples.push_back(*joints);
  }
  const double fraction = speed_fraction(speed_percent);
  const double cruise_s =
      std::max(travel.norm() / (kMaxLinearSpeedMS * fraction), turn_rad / (kMaxAngularSpeedRadS * fraction));
  return PlannedPath(std::move(samples), cruise_s);
}

JointValues PlannedPath::at(double t_s) const {
  const double u = profile_.progress(t_s) * static_cast<double>(samples_.size() - 1);
  const auto below = std::min(static_cast<std::size_t>(u), samples_.size() - 2);
  const double within = u - static_cast<double>(below);
  JointValues joints{};
  for (std::size_t j = 0; j < joints.size(); ++j) {
    joints[j] = samples_[below][j] + within * (samples_[below + 1][j] - samples_[below][j]);
  }
  return joints;
}

}  // namespace robotd::realman::sim
