// Between the motion layer's joint vectors (one value per joint) and the kinematics' fixed arrays.
#pragma once

#include <algorithm>
#include <cstddef>

#include "robotd/kinematics/arm_model.hpp"
#include "robotd/motion/trajectory.hpp"

namespace robotd::motion::detail {

/// The first min(size, 7) values; the rest 0 (the kinematics ignores entries from dof on).
inline kinematics::ArmJoints to_arm(const Joints& q) {
  kinematics::ArmJoints arm{};
  std::copy_n(q.begin(), std::min(q.size(), arm.size()), arm.begin());
  return arm;
}

/// The first `dof` values of `q`.
inline Joints to_joints(const kinematics::ArmJoints& q, std::size_t dof) {
  return {q.begin(), q.begin() + static_cast<std::ptrdiff_t>(dof)};
}

}  // namespace robotd::motion::detail
