// PAROL6 kinematics on the shared arm model "parol6" (robotd/kinematics/arm_model.hpp): the
// commander's standard-DH table and roll/pitch/yaw convention live there; this file converts
// between the driver's 6-joint vectors and Pose and the model's types. Forward kinematics and
// the pose conversions allocate nothing.
#include "parol6_kinematics.hpp"

#include <algorithm>
#include <cstddef>

#include "robotd/kinematics/arm_model.hpp"

namespace robotd::parol6 {
namespace {

kinematics::ArmJoints arm_joints(const JointVector& q) {
  kinematics::ArmJoints joints{};
  std::copy(q.begin(), q.end(), joints.begin());
  return joints;
}

JointVector joint_vector(const kinematics::ArmJoints& joints) {
  JointVector q{};
  std::copy_n(joints.begin(), q.size(), q.begin());
  return q;
}

}  // namespace

Eigen::Isometry3d tool_transform(const JointVector& q_rad) noexcept {
  return kinematics::tool_pose(parol6_model(), arm_joints(q_rad));
}

Pose forward_kinematics(const JointVector& q_rad) noexcept { return pose_of(tool_transform(q_rad)); }

Eigen::Isometry3d transform_of(const Pose& pose) noexcept {
  return kinematics::transform_of(
      kinematics::EulerConvention::kParol6Commander,
      {.position_m = {pose.x_m, pose.y_m, pose.z_m}, .angles_rad = {pose.roll_rad, pose.pitch_rad, pose.yaw_rad}});
}

Pose pose_of(const Eigen::Isometry3d& transform) noexcept {
  const kinematics::EulerPose pose = kinematics::pose_of(kinematics::EulerConvention::kParol6Commander, transform);
  return Pose{.x_m = pose.position_m[0],
              .y_m = pose.position_m[1],
              .z_m = pose.position_m[2],
              .roll_rad = pose.angles_rad[0],
              .pitch_rad = pose.angles_rad[1],
              .yaw_rad = pose.angles_rad[2]};
}

const kinematics::ArmModel& parol6_model() {
  static const kinematics::ArmModel& model = *kinematics::find_arm_model(kArmModelName);
  return model;
}

IkResult inverse_kinematics(const Pose& target, const JointVector& seed, const JointVector& min_rad,
                            const JointVector& max_rad) {
  const Eigen::Isometry3d goal = transform_of(target);
  // The shared solver's defaults: converged within 0.1 mm and 1e-3 rad, but polished on until
  // stuck, so that a Cartesian path lies on its line to well under a micrometre.
  const kinematics::IkSolution solved =
      kinematics::inverse_kinematics(parol6_model(), goal, arm_joints(seed), arm_joints(min_rad), arm_joints(max_rad),
                                     kinematics::IkOptions{.max_iterations = 300});
  return IkResult{.converged = solved.converged,
                  .q_rad = joint_vector(solved.q_rad),
                  .position_error_m = solved.position_error_m,
                  .orientation_error_rad = solved.orientation_error_rad};
}

}  // namespace robotd::parol6
