#include "joint_limits.hpp"

#include <algorithm>

namespace robotd::xarm::sim {

Result<JointValues> within_limits(const JointValues& joints, const ArmModel& model) {
  if (auto checked = check_joints_within(joints, model); !checked) return checked.error();
  JointValues onto = joints;
  for (std::size_t j = 0; j < model.dof; ++j) onto[j] = std::clamp(joints[j], model.min_rad[j], model.max_rad[j]);
  return onto;
}

JointValues home_joints(const ArmModel& model) {
  JointValues joints{};
  for (std::size_t j = 0; j < model.dof; ++j) joints[j] = std::clamp(0.0, model.min_rad[j], model.max_rad[j]);
  return joints;
}

}  // namespace robotd::xarm::sim
