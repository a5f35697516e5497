#include "piper_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

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

using Frames = std::array<Eigen::Isometry3d, kArmJoints>;  // joint frame i in the base frame
using Jacobian = Eigen::Matrix<double, 6, kArmJoints>;
using Twist = Eigen::Matrix<double, 6, 1>;  // position (m), then rotation vector (rad)

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

Frames joint_frames(const std::array<double, kArmJoints>& q_rad, DhVariant variant) {
  const auto& theta = variant == DhVariant::kOffset ? kOffsetTheta : kPlainTheta;
  Frames frames;
  Eigen::Isometry3d base_to_link = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < kDh.size(); ++i) {
    base_to_link = base_to_link * link_transform(kDh[i], q_rad[i] + theta[i]);
    frames[i] = base_to_link;
  }
  return frames;
}

/// Joint i turns about z of frame i: column i is (z × (tip − origin), z).
Jacobian geometric_jacobian(const Frames& frames) {
  const Eigen::Vector3d tip = frames.back().translation();
  Jacobian jacobian;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Eigen::Vector3d axis = frames[i].linear().col(2);
    const auto column = static_cast<Eigen::Index>(i);
    jacobian.block<3, 1>(0, column) = axis.cross(tip - frames[i].translation());
    jacobian.block<3, 1>(3, column) = axis;
  }
  return jacobian;
}

/// What moves `current` onto `target`, in the base frame.
Twist pose_error(const Eigen::Isometry3d& target, const Eigen::Isometry3d& current) {
  const Eigen::AngleAxisd rotation(target.linear() * current.linear().transpose());
  Twist error;
  error.head<3>() = target.translation() - current.translation();
  error.tail<3>() = rotation.angle() * rotation.axis();
  return error;
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
  constexpr int kMaxIterations = 200;
  // λ² of the damped step: shrinks after a step that lowers the error, grows after one that does not.
  constexpr double kInitialDamping = 1e-3;
  constexpr double kMinDamping = 1e-9;
  constexpr double kMaxDamping = 1e6;

  const Eigen::Isometry3d goal = transform_of(target);
  std::array<double, kArmJoints> q{};
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = std::max(min_rad[i], std::min(seed_rad[i], max_rad[i]));
  Frames frames = joint_frames(q, variant);
  Twist error = pose_error(goal, frames.back());
  double damping = kInitialDamping;
  int iteration = 0;
  for (; iteration < kMaxIterations && !within_tolerance(error); ++iteration) {
    Jacobian jacobian = geometric_jacobian(frames);
    Eigen::Matrix<double, kArmJoints, 1> step;
    // A joint at a limit that the step pushes further out is taken out of the step, which is then
    // solved again: clamping alone would leave the other joints a direction they cannot follow.
    for (int pass = 0; pass < kArmJoints; ++pass) {
      const Eigen::Matrix<double, 6, 6> normal =
          jacobian * jacobian.transpose() + damping * Eigen::Matrix<double, 6, 6>::Identity();
      step = jacobian.transpose() * normal.ldlt().solve(error);
      bool blocked = false;
      for (std::size_t i = 0; i < q.size(); ++i) {
        const auto joint = static_cast<Eigen::Index>(i);
        if ((q[i] <= min_rad[i] && step(joint) < 0) || (q[i] >= max_rad[i] && step(joint) > 0)) {
          jacobian.col(joint).setZero();
          blocked = true;
        }
      }
      if (!blocked) break;
    }
    std::array<double, kArmJoints> candidate{};
    for (std::size_t i = 0; i < q.size(); ++i) {
      candidate[i] = std::max(min_rad[i], std::min(q[i] + step(static_cast<Eigen::Index>(i)), max_rad[i]));
    }
    const Frames candidate_frames = joint_frames(candidate, variant);
    const Twist candidate_error = pose_error(goal, candidate_frames.back());
    if (candidate_error.squaredNorm() < error.squaredNorm()) {
      q = candidate;
      frames = candidate_frames;
      error = candidate_error;
      damping = std::max(damping * 0.3, kMinDamping);
    } else {
      damping = std::min(damping * 10.0, kMaxDamping);
    }
  }
  return IkResult{.converged = within_tolerance(error),
                  .q_rad = q,
                  .position_error_m = error.head<3>().norm(),
                  .orientation_error_rad = error.tail<3>().norm(),
                  .iterations = iteration};
}

}  // namespace robotd::piper
