#include "piper_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>

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

struct Limits {
  std::array<double, kArmJoints> min_rad;
  std::array<double, kArmJoints> max_rad;
};

IkResult solve(const Eigen::Isometry3d& goal, const std::array<double, kArmJoints>& seed_rad, DhVariant variant,
               const Limits& limits) {
  const kinematics::DlsResult solved = kinematics::solve_dls(
      goal, seed_rad, limits.min_rad, limits.max_rad,
      [variant](const kinematics::JointArray& q) { return joint_frames(q, variant); }, kinematics::DlsOptions{});
  return IkResult{.converged = within_tolerance(solved.error),
                  .q_rad = solved.q_rad,
                  .position_error_m = solved.error.head<3>().norm(),
                  .orientation_error_rad = solved.error.tail<3>().norm(),
                  .iterations = solved.iterations};
}

/// The largest single joint motion between two configurations: what a joint-space move takes longest over.
double joint_distance(const std::array<double, kArmJoints>& a, const std::array<double, kArmJoints>& b) {
  double largest = 0;
  for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  return largest;
}

/// From `from` to `to` in steps of at most 5 mm and 3°, each search seeded by the last solution:
/// the solution that continues the seed's branch.
IkResult walk(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to,
              const std::array<double, kArmJoints>& seed_rad, DhVariant variant, const Limits& limits) {
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
std::optional<std::array<double, kArmJoints>> wrist_flipped(const std::array<double, kArmJoints>& q_rad,
                                                            const Limits& limits) {
  std::array<double, kArmJoints> flipped = q_rad;
  flipped[4] = -q_rad[4];
  for (const std::size_t wrist : {std::size_t{3}, std::size_t{5}}) {
    flipped[wrist] = q_rad[wrist] + (q_rad[wrist] > 0 ? -kPi : kPi);
    if (flipped[wrist] < limits.min_rad[wrist] || flipped[wrist] > limits.max_rad[wrist]) return std::nullopt;
  }
  return flipped;
}

}  // namespace

Eigen::Isometry3d flange_transform(const std::array<double, kArmJoints>& q_rad, DhVariant variant) noexcept {
  return joint_frames(q_rad, variant).back();
}

std::array<CartesianPose, kArmJoints> link_poses(const std::array<double, kArmJoints>& q_rad,
                                                 DhVariant variant) noexcept {
  const ChainFrames frames = joint_frames(q_rad, variant);
  std::array<CartesianPose, kArmJoints> poses;
  for (std::size_t i = 0; i < poses.size(); ++i) poses[i] = pose_of(frames[i]);
  return poses;
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
      std::array<double, kArmJoints> realigned = found.q_rad;
      realigned[3] = seed_rad[3];
      realigned[5] = found.q_rad[5] + sense * (found.q_rad[3] - seed_rad[3]);
      consider(solve(transform_of(target), realigned, variant, limits));
    }
  }
  return best;
}

}  // namespace robotd::piper
