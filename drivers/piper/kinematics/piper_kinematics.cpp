#include "piper_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>

#include "robotd/kinematics/arm_model.hpp"
#include "robotd/kinematics/rotation.hpp"

namespace robotd::piper {
namespace {

constexpr double kPi = std::numbers::pi;

constexpr double radians(double degrees) { return degrees * kPi / 180.0; }

using Joints = std::array<double, kArmJoints>;

const kinematics::ArmModel& arm_model(DhVariant variant) {
  static const kinematics::ArmModel& offset = *kinematics::find_arm_model(arm_model_name(DhVariant::kOffset));
  static const kinematics::ArmModel& plain = *kinematics::find_arm_model(arm_model_name(DhVariant::kPlain));
  return variant == DhVariant::kOffset ? offset : plain;
}

kinematics::ArmJoints arm_joints(const Joints& q) {
  kinematics::ArmJoints joints{};
  std::copy(q.begin(), q.end(), joints.begin());
  return joints;
}

struct Limits {
  Joints min_rad;
  Joints max_rad;
};

IkResult solve(const Eigen::Isometry3d& goal, const Joints& seed_rad, DhVariant variant, const Limits& limits) {
  // Stops as soon as within the tolerance (0.1 mm, 1e-3 rad) or stuck after 200 refused steps.
  constexpr kinematics::IkOptions kOptions{.max_refusals = 200, .stop_position_m = 1e-4, .stop_orientation_rad = 1e-3};
  const kinematics::IkSolution solved = kinematics::inverse_kinematics(
      arm_model(variant), goal, arm_joints(seed_rad), arm_joints(limits.min_rad), arm_joints(limits.max_rad), kOptions);
  IkResult result{.converged = solved.converged,
                  .position_error_m = solved.position_error_m,
                  .orientation_error_rad = solved.orientation_error_rad,
                  .iterations = solved.iterations};
  std::copy_n(solved.q_rad.begin(), kArmJoints, result.q_rad.begin());
  return result;
}

/// The largest single joint motion between two configurations: what a joint-space move takes longest over.
double joint_distance(const Joints& a, const Joints& b) {
  double largest = 0;
  for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  return largest;
}

/// From `from` to `to` in steps of at most 5 mm and 3°, each search seeded by the last solution:
/// the solution that continues the seed's branch.
IkResult walk(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to, const Joints& seed_rad, DhVariant variant,
              const Limits& limits) {
  constexpr double kStepM = 5e-3;
  constexpr double kStepRad = radians(3.0);
  const Eigen::Quaterniond from_rotation(from.rotation());
  const Eigen::Quaterniond to_rotation(to.rotation());
  const double distance = (to.translation() - from.translation()).norm();
  const int steps = std::max(
      1,
      static_cast<int>(std::ceil(std::max(distance / kStepM, from_rotation.angularDistance(to_rotation) / kStepRad))));
  IkResult result{.q_rad = seed_rad};
  for (int k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    Eigen::Isometry3d goal = Eigen::Isometry3d::Identity();
    goal.linear() = from_rotation.slerp(t, to_rotation).toRotationMatrix();
    goal.translation() = from.translation() + t * (to.translation() - from.translation());
    result = solve(goal, result.q_rad, variant, limits);
    if (!result.converged) return result;
  }
  return result;
}

/// The other wrist solution's neighbourhood: J5 mirrored, J4 and J6 half a turn round; nullopt
/// when J4 or J6 would leave its limits.
std::optional<Joints> wrist_flipped(const Joints& q_rad, const Limits& limits) {
  Joints flipped = q_rad;
  flipped[4] = -q_rad[4];
  for (const std::size_t wrist : {std::size_t{3}, std::size_t{5}}) {
    flipped[wrist] = q_rad[wrist] + (q_rad[wrist] > 0 ? -kPi : kPi);
    if (flipped[wrist] < limits.min_rad[wrist] || flipped[wrist] > limits.max_rad[wrist]) return std::nullopt;
  }
  return flipped;
}

}  // namespace

std::string_view arm_model_name(DhVariant variant) noexcept {
  return variant == DhVariant::kOffset ? "piper" : "piper_plain_dh";
}

Eigen::Isometry3d flange_transform(const Joints& q_rad, DhVariant variant) noexcept {
  return kinematics::tool_pose(arm_model(variant), arm_joints(q_rad));
}

std::array<CartesianPose, kArmJoints> link_poses(const Joints& q_rad, DhVariant variant) noexcept {
  const auto frames = kinematics::link_frames(arm_model(variant), arm_joints(q_rad));
  std::array<CartesianPose, kArmJoints> poses;
  for (std::size_t i = 0; i < poses.size(); ++i) poses[i] = pose_of(frames[i]);
  return poses;
}

CartesianPose forward_kinematics(const Joints& q_rad, DhVariant variant) noexcept {
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
  return kinematics::transform_of(
      kinematics::EulerConvention::kFixedXyz,
      {.position_m = {pose.x_m, pose.y_m, pose.z_m}, .angles_rad = {pose.rx_rad, pose.ry_rad, pose.rz_rad}});
}

std::array<double, 4> quaternion_xyzw(const CartesianPose& pose) noexcept {
  return kinematics::quaternion_xyzw_from_rpy({pose.rx_rad, pose.ry_rad, pose.rz_rad});
}

IkResult inverse_kinematics(const CartesianPose& target, const Joints& seed_rad, DhVariant variant,
                            const Joints& min_rad, const Joints& max_rad) {
  const Limits limits{.min_rad = min_rad, .max_rad = max_rad};
  // Near the wrist singularity (J5 ≈ 0) a search from the seed alone can land on a distant
  // solution (a 20 mm move swinging J1 by 36°). Also walk there from the seed's pose in small
  // steps, each search seeded by the last, and try the wrist flipped; keep the nearest solution.
  IkResult best = solve(transform_of(target), seed_rad, variant, limits);
  const auto consider = [&](const IkResult& candidate) {
    if (!candidate.converged) return;
    if (!best.converged || joint_distance(candidate.q_rad, seed_rad) < joint_distance(best.q_rad, seed_rad)) {
      best = candidate;
    }
  };
  consider(walk(flange_transform(seed_rad, variant), transform_of(target), seed_rad, variant, limits));
  if (const auto flipped = wrist_flipped(seed_rad, limits))
    consider(solve(transform_of(target), *flipped, variant, limits));
  if (best.converged) {
    // With J5 near 0, J4 and J6 turn about nearly the same axis: only their sum (or difference)
    // matters, and the search may have split it far from the seed. Give J4 back its seed angle.
    const IkResult found = best;
    for (const double sense : {1.0, -1.0}) {
      Joints realigned = found.q_rad;
      realigned[3] = seed_rad[3];
      realigned[5] = found.q_rad[5] + sense * (found.q_rad[3] - seed_rad[3]);
      consider(solve(transform_of(target), realigned, variant, limits));
    }
  }
  return best;
}

}  // namespace robotd::piper
