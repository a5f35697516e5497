// A planned move's joints along its path, sampled at planning time: a straight line in joint
// space (move_joint, move_gohome) or a straight line of the TCP with its orientation turning
// about one axis (move_line), the joints solved every 1 mm and 10 mrad. The path's length is in
// the unit its speed and acceleration are given in: rad (the joint that moves most) or m (the
// TCP's travel, or its turn at 1 m per π rad — the controller's 1000 mm/s ↔ 180 °/s).
#pragma once

#include <cstddef>
#include <vector>

#include "arm_kinematics.hpp"
#include "codec/xarm_codec.hpp"
#include "robotd/result.hpp"

namespace robotd::xarm::sim {

class PlannedPath {
 public:
  static PlannedPath joint_line(const JointValues& from, const JointValues& to, std::size_t dof);
  /// kRefused saying where when a point is unreachable or the joints would jump (a singularity).
  static Result<PlannedPath> tcp_line(const ArmKinematics& kinematics, const Eigen::Isometry3d& tcp_offset,
                                      const JointValues& from, const Eigen::Isometry3d& to);

  double length() const { return length_; }
  /// The joints at path position `s` (0 … length()).
  JointValues at(double s) const;
  /// How fast the joints turn at path position `s` when the path is run at `speed` (its unit per
  /// second): the slope between the samples around `s`, as at() interpolates.
  JointValues velocity(double s, double speed) const;
  const JointValues& end() const { return samples_.back(); }

 private:
  PlannedPath(std::vector<JointValues> samples, double length) : samples_(std::move(samples)), length_(length) {}

  std::vector<JointValues> samples_;  // evenly spaced along the path
  double length_;
};

}  // namespace robotd::xarm::sim
