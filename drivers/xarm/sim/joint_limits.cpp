#include "joint_limits.hpp"

#include <algorithm>

namespace robotd::xarm::sim {
namespace {

constexpr double kRoundingRad = 1e-6;

}  // namespace

Result<JointValues> within_limits(const JointValues& joints, const ArmModel& model) {
  JointValues onto = joints;
  for (std::size_t j = 0; j < model.dof; ++j) {
    if (joints[j] >= model.min_rad[j] - kRoundingRad && joints[j] <= model.max_rad[j] + kRoundingRad) {
      onto[j] = std::clamp(joints[j], model.min_rad[j], model.max_rad[j]);
    }
  }
  if (auto checked = check_joints_within(onto, model); !checked) return checked.error();
  return onto;
}

JointValues home_joints(const ArmModel& model) {
  JointValues joints{};
  for (std::size_t j = 0; j < model.dof; ++j) joints[j] = std::clamp(0.0, model.min_rad[j], model.max_rad[j]);
  return joints;
}

}  // namespace robotd::xarm::sim
