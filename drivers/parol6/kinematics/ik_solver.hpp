// The damped-least-squares solver behind inverse_kinematics, on a goal transform, for the
// Cartesian planner's interpolated poses (a Pose round trip would lose precision at pitch ±90°).
// Internal to robotd_parol6_codec.
#pragma once

#include <Eigen/Geometry>

#include "kinematics/parol6_kinematics.hpp"

namespace robotd::parol6::detail {

IkResult solve_ik(const Eigen::Isometry3d& goal, const JointVector& seed, const JointVector& min_rad,
                  const JointVector& max_rad);

}  // namespace robotd::parol6::detail
