#include "linear_move.hpp"

#include <algorithm>

#include "kinematics/piper_kinematics.hpp"

namespace robotd::piper::sim {
namespace {

constexpr double kMinSpeed = 1e-6;

}  // namespace

LinearMove::LinearMove(const CartesianPose& from, const CartesianPose& to, double linear_speed_m_s,
                       double angular_speed_rad_s)
    : target_(to) {
  const Eigen::Isometry3d start = transform_of(from);
  const Eigen::Isometry3d end = transform_of(to);
  start_position_ = start.translation();
  end_position_ = end.translation();
  start_rotation_ = Eigen::Quaterniond(start.rotation());
  end_rotation_ = Eigen::Quaterniond(end.rotation());
  const double distance_m = (end_position_ - start_position_).norm();
  const double angle_rad = start_rotation_.angularDistance(end_rotation_);
  duration_s_ = std::max(distance_m / std::max(linear_speed_m_s, kMinSpeed),
                         angle_rad / std::max(angular_speed_rad_s, kMinSpeed));
}

CartesianPose LinearMove::advance(double dt_s) {
  elapsed_s_ = std::min(elapsed_s_ + std::max(dt_s, 0.0), duration_s_);
  if (done()) return target_;
  const double fraction = elapsed_s_ / duration_s_;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = start_rotation_.slerp(fraction, end_rotation_).toRotationMatrix();
  pose.translation() = start_position_ + fraction * (end_position_ - start_position_);
  return pose_of(pose);
}

}  // namespace robotd::piper::sim
