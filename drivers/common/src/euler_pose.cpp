// The vendors' ways of writing an orientation as three angles, both directions.
#include <cmath>
#include <numbers>

#include "robotd/kinematics/arm_model.hpp"

namespace robotd::kinematics {
namespace {

Eigen::Matrix3d rotation_of(EulerConvention convention, const std::array<double, 3>& angles) {
  const auto [a, b, c] = angles;
  if (convention == EulerConvention::kFixedXyz) {
    return (Eigen::AngleAxisd(c, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
  }
  return (Eigen::AngleAxisd(c, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

/// R = Rz(c)·Ry(b)·Rx(a): column 0 is (cb·cc, cb·sc, −sb), row 2 is (−sb, cb·sa, cb·ca).
std::array<double, 3> fixed_xyz_angles(const Eigen::Matrix3d& r) {
  constexpr double kGimbalLock = 1.0 - 1e-9;
  if (std::abs(r(2, 0)) < kGimbalLock) {
    return {std::atan2(r(2, 1), r(2, 2)), std::atan2(-r(2, 0), std::hypot(r(0, 0), r(1, 0))),
            std::atan2(r(1, 0), r(0, 0))};
  }
  // a and c turn about the same axis: all of it in c.
  return {0.0, std::copysign(std::numbers::pi / 2, -r(2, 0)), std::atan2(-r(0, 1), r(1, 1))};
}

/// R = Rx(c)·Ry(b)·Rz(a): row 0 is (cb·ca, −cb·sa, sb), column 2 is (sb, −sc·cb, cc·cb).
/// Within 1e-8 of cos b = 0 a and c turn about the same axis: a is 0 and c carries the turn, as
/// spatialmath's tr2rpy does (it snaps closer, at 10 ε, where the general formulas are already noisy).
std::array<double, 3> parol6_commander_angles(const Eigen::Matrix3d& r) {
  constexpr double kGimbalLock = 1e-8;
  const double cos_b = std::hypot(r(0, 0), r(0, 1));
  if (cos_b > kGimbalLock) {
    return {std::atan2(-r(0, 1), r(0, 0)), std::atan2(r(0, 2), cos_b), std::atan2(-r(1, 2), r(2, 2))};
  }
  if (r(0, 2) > 0) {
    return {0.0, std::numbers::pi / 2,
            std::atan2(r(2, 1), r(1, 1))};  // R = [[0, 0, 1], [s(a+c), c(a+c), 0], [−c(a+c), s(a+c), 0]]
  }
  return {0.0, -std::numbers::pi / 2,
          -std::atan2(r(1, 0), r(2, 0))};  // R = [[0, 0, −1], [s(a−c), c(a−c), 0], [c(a−c), −s(a−c), 0]]
}

}  // namespace

Eigen::Isometry3d transform_of(EulerConvention convention, const EulerPose& pose) noexcept {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = rotation_of(convention, pose.angles_rad);
  transform.translation() << pose.position_m[0], pose.position_m[1], pose.position_m[2];
  return transform;
}

EulerPose pose_of(EulerConvention convention, const Eigen::Isometry3d& transform) noexcept {
  const Eigen::Matrix3d r = transform.linear();
  const Eigen::Vector3d p = transform.translation();
  return EulerPose{
      .position_m = {p.x(), p.y(), p.z()},
      .angles_rad = convention == EulerConvention::kFixedXyz ? fixed_xyz_angles(r) : parol6_commander_angles(r)};
}

}  // namespace robotd::kinematics
