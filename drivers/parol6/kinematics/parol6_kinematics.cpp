// PAROL6 forward kinematics (the commander's standard-DH table, parol6_serial.md §11.1), the
// commander's roll/pitch/yaw convention, and a damped-least-squares inverse with joint limits.
// Forward kinematics and the pose conversions use fixed-size Eigen only: no allocation.
#include "parol6_kinematics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include <Eigen/Cholesky>

#include "ik_solver.hpp"

namespace robotd::parol6 {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMetresPerMm = 1e-3;

/// Row i of the standard DH table: link i = Rz(θ)·Tz(d)·Tx(a)·Rx(α), with θ = q_i (no offsets).
struct DhRow {
  double d_m;
  double a_m;
  double alpha_rad;
};

// Link 6 carries the commander's tool: 62.8 mm along the flange axis, 45.25 mm across it.
constexpr std::array<DhRow, kJoints> kDh{{
    {.d_m = 110.50 * kMetresPerMm, .a_m = 23.42 * kMetresPerMm, .alpha_rad = -kPi / 2},
    {.d_m = 0.0, .a_m = 180.00 * kMetresPerMm, .alpha_rad = kPi},
    {.d_m = 0.0, .a_m = -43.50 * kMetresPerMm, .alpha_rad = kPi / 2},
    {.d_m = -176.35 * kMetresPerMm, .a_m = 0.0, .alpha_rad = -kPi / 2},
    {.d_m = 0.0, .a_m = 0.0, .alpha_rad = kPi / 2},
    {.d_m = -62.80 * kMetresPerMm, .a_m = -45.25 * kMetresPerMm, .alpha_rad = kPi},
}};

/// frames[0] is the base; joint i turns about z of frames[i]; frames[6] is the tool.
using Frames = std::array<Eigen::Isometry3d, kJoints + 1>;
using Jacobian = Eigen::Matrix<double, 6, kJoints>;
using Twist = Eigen::Matrix<double, 6, 1>;  // position (m), then rotation vector (rad)

Eigen::Isometry3d link_transform(const DhRow& row, double theta_rad) {
  const double ct = std::cos(theta_rad);
  const double st = std::sin(theta_rad);
  const double ca = std::cos(row.alpha_rad);
  const double sa = std::sin(row.alpha_rad);
  Eigen::Isometry3d link = Eigen::Isometry3d::Identity();
  link.linear() << ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0.0, sa, ca;
  link.translation() << row.a_m * ct, row.a_m * st, row.d_m;
  return link;
}

Frames joint_frames(const JointVector& q_rad) {
  Frames frames;
  frames[0] = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < kDh.size(); ++i) frames[i + 1] = frames[i] * link_transform(kDh[i], q_rad[i]);
  return frames;
}

/// Column i: joint i's axis z_i through o_i moves the tool by z_i × (tip − o_i) and turns it about z_i.
Jacobian geometric_jacobian(const Frames& frames) {
  const Eigen::Vector3d tip = frames.back().translation();
  Jacobian jacobian;
  for (std::size_t i = 0; i < kDh.size(); ++i) {
    const Eigen::Vector3d axis = frames[i].linear().col(2);
    const auto column = static_cast<Eigen::Index>(i);
    jacobian.block<3, 1>(0, column) = axis.cross(tip - frames[i].translation());
    jacobian.block<3, 1>(3, column) = axis;
  }
  return jacobian;
}

/// The twist that takes `current` onto `goal`, in the base frame.
Twist pose_error(const Eigen::Isometry3d& goal, const Eigen::Isometry3d& current) {
  const Eigen::AngleAxisd rotation(goal.linear() * current.linear().transpose());
  Twist error;
  error.head<3>() = goal.translation() - current.translation();
  error.tail<3>() = rotation.angle() * rotation.axis();
  return error;
}

bool converged(const Twist& error) {
  constexpr double kPositionToleranceM = 1e-4;
  constexpr double kOrientationToleranceRad = 1e-3;
  return error.head<3>().norm() < kPositionToleranceM && error.tail<3>().norm() < kOrientationToleranceRad;
}

/// Where the solver stops: far below the convergence tolerance, so that a Cartesian path lies on
/// its line to well under a micrometre, not merely within 0.1 mm.
bool polished(const Twist& error) {
  constexpr double kPositionM = 1e-10;
  constexpr double kOrientationRad = 1e-10;
  return error.head<3>().norm() < kPositionM && error.tail<3>().norm() < kOrientationRad;
}

JointVector clamped(const JointVector& q, const JointVector& min_rad, const JointVector& max_rad) {
  JointVector out{};
  for (std::size_t i = 0; i < q.size(); ++i) out[i] = std::max(min_rad[i], std::min(q[i], max_rad[i]));
  return out;
}

}  // namespace

Eigen::Isometry3d tool_transform(const JointVector& q_rad) noexcept { return joint_frames(q_rad).back(); }

Pose forward_kinematics(const JointVector& q_rad) noexcept { return pose_of(tool_transform(q_rad)); }

Eigen::Isometry3d transform_of(const Pose& pose) noexcept {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  // spatialmath's SE3.RPY([roll, pitch, yaw], order="xyz"): R = Rx(yaw)·Ry(pitch)·Rz(roll).
  transform.linear() = (Eigen::AngleAxisd(pose.yaw_rad, Eigen::Vector3d::UnitX()) *
                        Eigen::AngleAxisd(pose.pitch_rad, Eigen::Vector3d::UnitY()) *
                        Eigen::AngleAxisd(pose.roll_rad, Eigen::Vector3d::UnitZ()))
                           .toRotationMatrix();
  transform.translation() << pose.x_m, pose.y_m, pose.z_m;
  return transform;
}

Pose pose_of(const Eigen::Isometry3d& transform) noexcept {
  // With R = Rx(c)·Ry(b)·Rz(a): row 0 is (cb·ca, −cb·sa, sb), column 2 is (sb, −sc·cb, cc·cb).
  // Within 1e-8 of cos(pitch) = 0 roll and yaw turn about the same axis: roll is set to 0 and
  // yaw carries the turn, as spatialmath's tr2rpy does (it snaps closer, at 10 ε, where the
  // general formulas are already noisy).
  constexpr double kGimbalLock = 1e-8;
  const Eigen::Matrix3d r = transform.linear();
  Pose pose{.x_m = transform.translation().x(), .y_m = transform.translation().y(), .z_m = transform.translation().z()};
  const double cos_pitch = std::hypot(r(0, 0), r(0, 1));
  if (cos_pitch > kGimbalLock) {
    pose.roll_rad = std::atan2(-r(0, 1), r(0, 0));
    pose.pitch_rad = std::atan2(r(0, 2), cos_pitch);
    pose.yaw_rad = std::atan2(-r(1, 2), r(2, 2));
  } else if (r(0, 2) > 0) {
    pose.pitch_rad = kPi / 2;  // R = [[0, 0, 1], [sin(a + c), cos(a + c), 0], [−cos(a + c), sin(a + c), 0]]
    pose.yaw_rad = std::atan2(r(2, 1), r(1, 1));
  } else {
    pose.pitch_rad = -kPi / 2;  // R = [[0, 0, −1], [sin(a − c), cos(a − c), 0], [cos(a − c), −sin(a − c), 0]]
    pose.yaw_rad = -std::atan2(r(1, 0), r(2, 0));
  }
  return pose;
}

IkResult inverse_kinematics(const Pose& target, const JointVector& seed, const JointVector& min_rad,
                            const JointVector& max_rad) {
  return detail::solve_ik(transform_of(target), seed, min_rad, max_rad);
}

IkResult detail::solve_ik(const Eigen::Isometry3d& goal, const JointVector& seed, const JointVector& min_rad,
                          const JointVector& max_rad) {
  constexpr int kMaxIterations = 300;
  // Consecutive refused steps after which the search is stuck (the damping has grown 10^12-fold):
  // at the solution's numerical floor, in a local minimum, or against the limits.
  constexpr int kMaxRefusals = 12;
  // λ² of the damped step: shrinks after a step that lowers the error, grows after one that does not.
  constexpr double kInitialDamping = 1e-3;
  constexpr double kMinDamping = 1e-9;
  constexpr double kMaxDamping = 1e6;

  JointVector q = clamped(seed, min_rad, max_rad);
  Frames frames = joint_frames(q);
  Twist error = pose_error(goal, frames.back());
  double damping = kInitialDamping;
  int refusals = 0;
  for (int iteration = 0; iteration < kMaxIterations && refusals < kMaxRefusals && !polished(error); ++iteration) {
    Jacobian jacobian = geometric_jacobian(frames);
    Eigen::Matrix<double, kJoints, 1> step;
    // A joint held at a limit by the step is taken out of it and the step solved again, so the
    // other joints get a direction they can actually follow.
    for (int pass = 0; pass < kJoints; ++pass) {
      const Eigen::Matrix<double, 6, 6> normal =
          jacobian * jacobian.transpose() + damping * Eigen::Matrix<double, 6, 6>::Identity();
      step = jacobian.transpose() * normal.ldlt().solve(error);
      bool blocked = false;
      for (std::size_t i = 0; i < q.size(); ++i) {
        const auto joint = static_cast<Eigen::Index>(i);
        const bool pushed_out = (q[i] <= min_rad[i] && step(joint) < 0) || (q[i] >= max_rad[i] && step(joint) > 0);
        if (pushed_out) {
          jacobian.col(joint).setZero();
          blocked = true;
        }
      }
      if (!blocked) break;
    }
    JointVector candidate{};
    for (std::size_t i = 0; i < q.size(); ++i) candidate[i] = q[i] + step(static_cast<Eigen::Index>(i));
    candidate = clamped(candidate, min_rad, max_rad);
    const Frames candidate_frames = joint_frames(candidate);
    const Twist candidate_error = pose_error(goal, candidate_frames.back());
    if (candidate_error.squaredNorm() < error.squaredNorm()) {
      q = candidate;
      frames = candidate_frames;
      error = candidate_error;
      damping = std::max(damping * 0.3, kMinDamping);
      refusals = 0;
    } else {
      damping = std::min(damping * 10.0, kMaxDamping);
      ++refusals;
    }
  }
  return IkResult{.converged = converged(error),
                  .q_rad = q,
                  .position_error_m = error.head<3>().norm(),
                  .orientation_error_rad = error.tail<3>().norm()};
}

}  // namespace robotd::parol6
