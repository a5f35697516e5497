#include "arm_kinematics.hpp"

#include <array>

namespace robotd::realman::sim {

std::optional<ArmKinematics> ArmKinematics::for_product(std::string_view product_version, const ArmModel& model) {
  const kinematics::ArmModel* geometry = kinematics::find_arm_model(kinematic_model_of(product_version));
  if (geometry == nullptr) return std::nullopt;
  return ArmKinematics(*geometry, model);
}

DhRow ArmKinematics::row(std::size_t joint) const {
  const kinematics::DhLink& link = geometry_->links[joint];
  DhRow row{.a_m = link.a_m, .alpha_rad = link.alpha_rad, .d_m = link.d_m, .offset_rad = link.theta_offset_rad};
  // A force version's longer flange is the model's tool along the last axis.
  if (joint + 1 == dof()) row.d_m += geometry_->tool.translation().z();
  return row;
}

Eigen::Isometry3d ArmKinematics::flange(const JointValues& joints_rad) const {
  return kinematics::tool_pose(*geometry_, joints_rad);
}

std::optional<JointValues> ArmKinematics::solve(const Eigen::Isometry3d& goal, const JointValues& seed) const {
  const kinematics::IkOptions options{.max_refusals = 200,
                                      .stop_position_m = 1e-6,
                                      .stop_orientation_rad = 1e-4,
                                      .converged_position_m = 1e-5,
                                      .converged_orientation_rad = 1e-3};
  // From the seed first (the nearest solution, so paths stay continuous); then from a few fixed
  // postures, for targets the seed's branch cannot reach.
  const std::array<JointValues, 5> starts{
      seed, JointValues{0, 0.5, 1.0, 0, 1.0, 0}, JointValues{0, -0.5, -1.0, 0, -1.0, 0},
      JointValues{1.5, 0.5, 1.0, 1.5, -1.0, 0}, JointValues{-1.5, -0.5, -1.0, -1.5, 1.0, 0}};
  for (const JointValues& start : starts) {
    const kinematics::IkSolution result =
        kinematics::inverse_kinematics(*geometry_, goal, start, model_.min_rad, model_.max_rad, options);
    if (result.converged) return result.q_rad;
  }
  return std::nullopt;
}

Eigen::Isometry3d isometry_of(const EulerPose& pose) {
  return kinematics::transform_of(kinematics::EulerConvention::kFixedXyz,
                                  {.position_m = pose.position_m, .angles_rad = pose.euler_rad});
}

EulerPose euler_pose_of(const Eigen::Isometry3d& pose) {
  const kinematics::EulerPose angles = kinematics::pose_of(kinematics::EulerConvention::kFixedXyz, pose);
  EulerPose out;
  out.position_m = angles.position_m;
  out.euler_rad = angles.angles_rad;
  return out;
}

}  // namespace robotd::realman::sim
