#include "arm_kinematics.hpp"

#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace robotd::xarm::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSameAngleRad = 1e-12;
/// The 7-joint arms' redundant joint, held during inverse kinematics (index from 0).
constexpr std::size_t kHeldJointOf7 = 2;

}  // namespace

ArmKinematics ArmKinematics::for_model(const ArmModel& model) {
  const kinematics::ArmModel* geometry = kinematics::find_arm_model(model.kinematic_model);
  if (geometry == nullptr) {
    throw std::logic_error("xArm model " + std::string(model.name) + " names no arm geometry");
  }
  return ArmKinematics(*geometry, model);
}

Eigen::Isometry3d ArmKinematics::flange(const JointValues& joints_rad) const {
  return kinematics::tool_pose(*geometry_, joints_rad);
}

Eigen::Isometry3d ArmKinematics::tcp(const JointValues& joints_rad, const Eigen::Isometry3d& tcp_offset) const {
  return flange(joints_rad) * tcp_offset;
}

std::optional<JointValues> ArmKinematics::solve(const Eigen::Isometry3d& goal, const Eigen::Isometry3d& tcp_offset,
                                                const JointValues& seed) const {
  if (!solves_poses()) return std::nullopt;
  kinematics::ArmModel with_tcp = *geometry_;
  with_tcp.tool = geometry_->tool * tcp_offset;
  JointValues min_rad = model_.min_rad;
  JointValues max_rad = model_.max_rad;
  const bool redundant = dof() == 7;
  if (redundant) {
    min_rad[kHeldJointOf7] = seed[kHeldJointOf7];
    max_rad[kHeldJointOf7] = seed[kHeldJointOf7];
  }

  // From the seed first (the nearest solution keeps paths continuous), then from postures in the
  // middle of the limits, turned about the base and the forearm.
  const std::size_t forearm = redundant ? 4 : 3;
  std::vector<JointValues> starts{seed};
  JointValues middle{};
  for (std::size_t i = 0; i < dof(); ++i) middle[i] = 0.5 * (min_rad[i] + max_rad[i]);
  for (const double base : {0.0, kPi / 2, -kPi / 2, kPi}) {
    JointValues start = middle;
    start[0] = base;
    starts.push_back(start);
    start[forearm] = kPi / 2;
    starts.push_back(start);
  }
  const kinematics::IkOptions options{.max_refusals = 200,
                                      .stop_position_m = 1e-6,
                                      .stop_orientation_rad = 1e-4,
                                      .converged_position_m = 1e-5,
                                      .converged_orientation_rad = 1e-3};
  for (const JointValues& start : starts) {
    const kinematics::IkSolution result =
        kinematics::inverse_kinematics(with_tcp, goal, start, min_rad, max_rad, options);
    if (result.converged) return result.q_rad;
  }
  return std::nullopt;
}

Eigen::Isometry3d isometry_of(const Pose& pose) {
  return kinematics::transform_of(kinematics::EulerConvention::kFixedXyz,
                                  {.position_m = pose.position_m, .angles_rad = pose.rpy_rad});
}

Pose pose_of(const Eigen::Isometry3d& transform) {
  const kinematics::EulerPose pose = kinematics::pose_of(kinematics::EulerConvention::kFixedXyz, transform);
  Pose out{.position_m = pose.position_m, .rpy_rad = pose.angles_rad};
  // −180° and 180° are the same turn; the controller writes 180° (atan2 of −0 gives −180°).
  for (double& angle : out.rpy_rad) {
    if (angle <= -kPi + kSameAngleRad) angle = kPi;
  }
  return out;
}

}  // namespace robotd::xarm::sim
