// MOVE L as the simulator models it: the flange pose travels on a straight line from where the
// arm is to the target at constant speed (linear and angular speed limits, whichever is slower),
// the orientation slerped along the way. The arm model solves IK for the poses it hands out.
#pragma once

#include <Eigen/Geometry>

#include "codec/piper_frames.hpp"

namespace robotd::piper::sim {

class LinearMove {
 public:
  /// `linear_speed_m_s` and `angular_speed_rad_s` > 0: the speeds along the line.
  LinearMove(const CartesianPose& from, const CartesianPose& to, double linear_speed_m_s, double angular_speed_rad_s);

  /// The pose `dt_s` further along the line (the target once the time is up).
  CartesianPose advance(double dt_s);
  bool done() const { return elapsed_s_ >= duration_s_; }
  const CartesianPose& target() const { return target_; }
  double duration_s() const { return duration_s_; }

 private:
  CartesianPose target_;
  Eigen::Vector3d start_position_;
  Eigen::Vector3d end_position_;
  Eigen::Quaterniond start_rotation_;
  Eigen::Quaterniond end_rotation_;
  double duration_s_ = 0;
  double elapsed_s_ = 0;
};

}  // namespace robotd::piper::sim
