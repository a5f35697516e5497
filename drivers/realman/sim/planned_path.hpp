// A planned motion's joints over its own time: a path in joint space (sampled uniformly in a
// path parameter u from 0 to 1) run on a trapezoidal speed profile. movej and movej_p are a
// straight line in joint space (two samples); movel is a straight line of the flange with the
// joints solved along it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "arm_kinematics.hpp"
#include "codec/realman_codec.hpp"
#include "robotd/result.hpp"

namespace robotd::realman::sim {

/// Progress u from 0 to 1 over time: constant acceleration for kRampS, constant speed, constant
/// deceleration for kRampS; a shorter path gets a triangle with the same acceleration.
class MotionProfile {
 public:
  static constexpr double kRampS = 0.25;

  MotionProfile() = default;
  /// `cruise_s`: how long the whole path would take at full speed (0: a path of no length).
  explicit MotionProfile(double cruise_s);
  double duration_s() const { return duration_s_; }
  double progress(double t_s) const;

 private:
  double duration_s_ = 0;
  double ramp_s_ = 0;
  double peak_speed_ = 0;  // du/dt at cruise
};

/// The planned speeds (spec §3.1 "v" is a percentage of these).
inline constexpr double kMaxJointSpeedRadS = kPassThroughMaxSpeedRadS;  // 180 °/s
inline constexpr double kMaxLinearSpeedMS = 0.25;
inline constexpr double kMaxAngularSpeedRadS = kPassThroughMaxSpeedRadS;

class PlannedPath {
 public:
  /// A straight line in joint space at `speed_percent` of 180 °/s for the joint that moves most.
  static PlannedPath joint_line(const JointValues& from, const JointValues& to, std::size_t dof, int speed_percent);
  /// A straight line of the flange from where `from` puts it to `to`, the orientation turning
  /// about one axis, at `speed_percent` of 0.25 m/s and 180 °/s; the joints solved every 1 mm
  /// and 10 mrad. kRefused when a point is unreachable or the joints would jump (a singularity).
  static Result<PlannedPath> cartesian_line(const ArmKinematics& kinematics, const JointValues& from,
                                            const EulerPose& to, int speed_percent);

  double duration_s() const { return profile_.duration_s(); }
  JointValues at(double t_s) const;
  const JointValues& end() const { return samples_.back(); }

 private:
  PlannedPath(std::vector<JointValues> samples, double cruise_s) : samples_(std::move(samples)), profile_(cruise_s) {}

  std::vector<JointValues> samples_;  // at u = k / (size − 1)
  MotionProfile profile_;
};

}  // namespace robotd::realman::sim
