#include "piper_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "robotd/kinematics/serial_chain.hpp"

namespace robotd::piper {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMetresPerMm = 1e-3;

constexpr double radians(double degrees) { return degrees * kPi / 180.0; }

/// Row i of the modified (Craig) DH table: link i = RotX(α)·TransX(a)·RotZ(θ + q)·TransZ(d).
struct DhRow {
  double alpha_rad;
  double a_m;
  double d_m;
};

constexpr std::array<DhRow, kArmJoints> kDh{{
    {.alpha_rad = 0.0, .a_m = 0.0, .d_m = 123.0 * kMetresPerMm},
    {.alpha_rad = -kPi / 2, .a_m = 0.0, .d_m = 0.0},
    {.alpha_rad = 0.0, .a_m = 285.03 * kMetresPerMm, .d_m = 0.0},
    {.alpha_rad = kPi / 2, .a_m = -21.98 * kMetresPerMm, .d_m = 250.75 * kMetresPerMm},
    {.alpha_rad = -kPi / 2, .a_m = 0.0, .d_m = 0.0},
    {.alpha_rad = kPi / 2, .a_m = 0.0, .d_m = 91.0 * kMetresPerMm},
}};

// θ offsets: the two variants move 2° between J2 and J3 (their sum stays −275°).
constexpr std::array<double, kArmJoints> kOffsetTheta{0, radians(-172.22), radians(-102.78), 0, 0, 0};
constexpr std::array<double, kArmJoints> kPlainTheta{0, radians(-174.22), radians(-100.78), 0, 0, 0};

using kinematics::ChainFrames;
using kinematics::Twist;

Eigen::Isometry3d link_transform(const DhRow& row, double theta_rad) {
  const double ca = std::cos(row.alpha_rad);
  const double sa = std::sin(row.alpha_rad);
  const double ct = std::cos(theta_rad);
  const double st = std::sin(theta_rad);
  Eigen::Isometry3d link = Eigen::Isometry3d::Identity();
  link.linear() << ct, -st, 0.0, st * ca, ct * ca, -sa, st * sa, ct * sa, ca;
  link.translation() << row.a_m, -sa * row.d_m, ca * row.d_m;
  return link;
}

/// Joint i turns about z of frame i (the modified-DH frame after link i); the tip is frame 6.
ChainFrames joint_frames(const std::array<double, kArmJoints>& q_rad, DhVariant variant) {
  const auto& theta = variant == DhVariant::kOffset ? kOffsetTheta : kPlainTheta;
  ChainFrames frames;
  Eigen::Isometry3d base_to_link = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < kDh.size(); ++i) {
    base_to_link = base_to_link * link_transform(kDh[i], q_rad[i] + theta[i]);
    frames[i] = base_to_link;
  }
  frames[kArmJoints] = base_to_link;  // the flange is joint 6's frame
  return frames;
}

Eigen::Quaterniond rotation_of(const CartesianPose& pose) {
  return Eigen::AngleAxisd(pose.rz_rad, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pose.ry_rad, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(pose.rx_rad, Eigen::Vector3d::UnitX());
}

bool within_tolerance(const Twist& error) {
  constexpr double kPositionToleranceM = 1e-4;
  constexpr double kOrientationToleranceRad = 1e-3;
  return error.head<3>().norm() < kPositionToleranceM && error.tail<3>().norm() < kOrientationToleranceRad;
}

}  // namespace

Eigen::Isometry3d flange_transform(const std::array<double, kArmJoints>& q_rad, DhVariant variant) noexcept {
  return joint_frames(q_rad, variant).back();
}

CartesianPose forward_kinematics(const std::array<double, kArmJoints>& q_rad, DhVariant variant) noexcept {
  return pose_of(flange_transform(q_rad, variant));
}

CartesianPose pose_of(const Eigen::Isometry3d& flange) noexcept {
  constexpr double kGimbalLock = 1.0 - 1e-4;  // the SDK's threshold on |r20|
  const Eigen::Matrix3d rotation = flange.linear();
  const Eigen::Vector3d position = flange.translation();
  CartesianPose pose{.x_m = position.x(), .y_m = position.y(), .z_m = position.z()};
  const double r20 = rotation(2, 0);
  if (r20 < -kGimbalLock) {
    pose.ry_rad = kPi / 2;
    pose.rx_rad = std::atan2(rotation(0, 1), rotation(1, 1));
  } else if (r20 > kGimbalLock) {
    pose.ry_rad = -kPi / 2;
    pose.rx_rad = -std::atan2(rotation(0, 1), rotation(1, 1));
  } else {
    pose.rx_rad = std::atan2(rotation(2, 1), rotation(2, 2));
    pose.ry_rad = std::atan2(-r20, std::hypot(rotation(0, 0), rotation(1, 0)));
    pose.rz_rad = std::atan2(rotation(1, 0), rotation(0, 0));
  }
  return pose;
}

Eigen::Isometry3d transform_of(const CartesianPose& pose) noexcept {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = rotation_of(pose).toRotationMatrix();
  transform.translation() << pose.x_m, pose.y_m, pose.z_m;
  return transform;
}

std::array<double, 4> quaternion_xyzw(const CartesianPose& pose) noexcept {
  const Eigen::Quaterniond rotation = rotation_of(pose);
  return {rotation.x(), rotation.y(), rotation.z(), rotation.w()};
}

IkResult inverse_kinematics(const CartesianPose& target, const std::array<double, kArmJoints>& seed_rad,
                            DhVariant variant, const std::array<double, kArmJoints>& min_rad,
                            const std::array<double, kArmJoints>& max_rad) {
  const kinematics::DlsResult solved = kinematics::solve_dls(
      transform_of(target), seed_rad, min_rad, max_rad,
      [variant](const kinematics::JointArray& q) { return joint_frames(q, variant); }, kinematics::DlsOptions{});
  return IkResult{.converged = within_tolerance(solved.error),
                  .q_rad = solved.q_rad,
                  .position_error_m = solved.error.head<3>().norm(),
                  .orientation_error_rad = solved.error.tail<3>().norm(),
                  .iterations = solved.iterations};
}

}  // namespace robotd::piper
