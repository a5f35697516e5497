// PAROL6 forward kinematics (the commander's standard-DH table, parol6_serial.md §11.1), the
// commander's roll/pitch/yaw convention, and a damped-least-squares inverse with joint limits.
// Forward kinematics and the pose conversions use fixed-size Eigen only: no allocation.
#include "parol6_kinematics.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "ik_solver.hpp"
#include "robotd/kinematics/serial_chain.hpp"

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

/// frames[0] is the base; joint i turns about z of frames[i]; frames[6] is the tool.
kinematics::ChainFrames joint_frames(const JointVector& q_rad) {
  kinematics::ChainFrames frames;
  frames[0] = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < kDh.size(); ++i) frames[i + 1] = frames[i] * link_transform(kDh[i], q_rad[i]);
  return frames;
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
  // The search goes on far below the convergence tolerance (it stops once stuck, after 12 refused
  // steps), so that a Cartesian path lies on its line to well under a micrometre, not merely
  // within 0.1 mm.
  constexpr kinematics::DlsOptions kPolish{
      .max_iterations = 300, .max_refusals = 12, .stop_position_m = 1e-10, .stop_orientation_rad = 1e-10};
  constexpr double kConvergedPositionM = 1e-4;
  constexpr double kConvergedOrientationRad = 1e-3;
  const kinematics::DlsResult solved = kinematics::solve_dls(goal, seed, min_rad, max_rad, joint_frames, kPolish);
  const double position_error_m = solved.error.head<3>().norm();
  const double orientation_error_rad = solved.error.tail<3>().norm();
  return IkResult{
      .converged = position_error_m < kConvergedPositionM && orientation_error_rad < kConvergedOrientationRad,
      .q_rad = solved.q_rad,
      .position_error_m = position_error_m,
      .orientation_error_rad = orientation_error_rad};
}

}  // namespace robotd::parol6
