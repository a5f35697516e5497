#include "arm_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "robotd/kinematics/serial_chain.hpp"

namespace robotd::xarm::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMm = 1e-3;
constexpr double kDeg = kPi / 180.0;
constexpr double kSolvedPositionM = 1e-5;
constexpr double kSolvedOrientationRad = 1e-3;
constexpr double kSameAngleRad = 1e-12;
/// The 7-joint arms' redundant joint, held during inverse kinematics (index from 0).
constexpr std::size_t kHeldJointOf7 = 2;

DhRow row(double d_mm, double a_mm, double alpha_rad, double offset_rad) {
  return DhRow{.d_m = d_mm * kMm, .a_m = a_mm * kMm, .alpha_rad = alpha_rad, .offset_rad = offset_rad};
}

// Standard D-H tables from UFACTORY's "Kinematic and Dynamic Parameters" pages
// (xArm-Developer/ufactory_docs: support_articles/developer/kinematic-and-dynamic-parameters/
// xarm-series/xarm-5-lite.md, xarm-6.md, xarm-7.md, lite6.md, ufactory-850.md). The xArm 5 and 6
// upper arm is 284.5 mm up and 53.5 mm forward: a2 = 289.48866 mm at −79.34995°; the xArm 5
// forearm and wrist fold into a3 = 351.158796 mm (77.5 mm forward, 342.5 mm down).
std::vector<DhRow> xarm5_rows() {
  return {row(267, 0, -kPi / 2, 0), row(0, 289.48866, 0, -1.3849179), row(0, 351.158796, 0, 2.7331843),
          row(0, 76, -kPi / 2, -1.3482664), row(97, 0, 0, 0)};
}

std::vector<DhRow> xarm6_rows() {
  return {row(267, 0, -kPi / 2, 0),  row(0, 289.48866, 0, -1.3849179), row(0, 77.5, -kPi / 2, 1.3849179),
          row(342.5, 0, kPi / 2, 0), row(0, 76, -kPi / 2, 0),          row(97, 0, 0, 0)};
}

std::vector<DhRow> xarm7_rows() {
  return {row(267, 0, -kPi / 2, 0), row(0, 0, kPi / 2, 0),     row(293, 52.5, kPi / 2, 0),
          row(0, 77.5, kPi / 2, 0), row(342.5, 0, kPi / 2, 0), row(0, 76, -kPi / 2, 0),
          row(97, 0, 0, 0)};
}

std::vector<DhRow> lite6_rows() {
  return {row(243.3, 0, -90 * kDeg, 0),      row(0, 200, 180 * kDeg, -90 * kDeg),
          row(0, 87, 90 * kDeg, -90 * kDeg), row(227.6, 0, 90 * kDeg, 0),
          row(0, 0, -90 * kDeg, 0),          row(61.5, 0, 0, 0)};
}

std::vector<DhRow> uf850_rows() {
  return {row(364, 0, 90 * kDeg, 0),
          row(0, 390, 180 * kDeg, 90 * kDeg),
          row(0, 150, -90 * kDeg, 90 * kDeg),
          row(426, 0, -90 * kDeg, 0),
          row(0, 0, 90 * kDeg, 0),
          row(90, 0, 0, 0)};
}

constexpr int kLite6Type = 9;
constexpr int kUf850Type = 12;

Eigen::Isometry3d link(const DhRow& dh, double q_rad) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.rotate(Eigen::AngleAxisd(q_rad + dh.offset_rad, Eigen::Vector3d::UnitZ()));
  transform.translate(Eigen::Vector3d(dh.a_m, 0, dh.d_m));  // Tz(d)·Tx(a): both along the turned axes
  transform.rotate(Eigen::AngleAxisd(dh.alpha_rad, Eigen::Vector3d::UnitX()));
  return transform;
}

bool solved(const kinematics::Twist& error) {
  return error.head<3>().norm() < kSolvedPositionM && error.tail<3>().norm() < kSolvedOrientationRad;
}

}  // namespace

ArmKinematics ArmKinematics::for_model(const ArmModel& model) {
  if (model.dof == 5) return ArmKinematics(xarm5_rows(), model);
  if (model.dof == 7) return ArmKinematics(xarm7_rows(), model);
  if (model.type_code == kLite6Type) return ArmKinematics(lite6_rows(), model);
  if (model.type_code == kUf850Type) return ArmKinematics(uf850_rows(), model);
  return ArmKinematics(xarm6_rows(), model);
}

Eigen::Isometry3d ArmKinematics::flange(const JointValues& joints_rad) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < rows_.size(); ++i) pose = pose * link(rows_[i], joints_rad[i]);
  return pose;
}

Eigen::Isometry3d ArmKinematics::tcp(const JointValues& joints_rad, const Eigen::Isometry3d& tcp_offset) const {
  return flange(joints_rad) * tcp_offset;
}

std::optional<JointValues> ArmKinematics::solve(const Eigen::Isometry3d& goal, const Eigen::Isometry3d& tcp_offset,
                                                const JointValues& seed) const {
  if (!solves_poses()) return std::nullopt;
  using kinematics::JointArray;
  // The chain's joints: all six of a 6-joint arm; a 7-joint arm's without its held joint.
  std::vector<std::size_t> free;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    if (rows_.size() != 7 || i != kHeldJointOf7) free.push_back(i);
  }
  JointArray min_rad{};
  JointArray max_rad{};
  for (std::size_t k = 0; k < kinematics::kChainJoints; ++k) {
    min_rad[k] = model_.min_rad[free[k]];
    max_rad[k] = model_.max_rad[free[k]];
  }
  const auto joints_of = [&free, &seed](const JointArray& q) {
    JointValues joints = seed;
    for (std::size_t k = 0; k < kinematics::kChainJoints; ++k) joints[free[k]] = q[k];
    return joints;
  };
  const auto frames_of = [this, &free, &joints_of, &tcp_offset](const JointArray& q) {
    const JointValues joints = joints_of(q);
    kinematics::ChainFrames frames;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    std::size_t k = 0;
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      if (k < free.size() && free[k] == i) frames[k++] = pose;  // joint i turns about frame i−1's z axis
      pose = pose * link(rows_[i], joints[i]);
    }
    frames[kinematics::kChainJoints] = pose * tcp_offset;
    return frames;
  };

  // From the seed first (the nearest solution keeps paths continuous), then from postures in the
  // middle of the limits, turned about the base and the forearm.
  std::vector<JointArray> starts(1);
  JointArray middle{};
  for (std::size_t k = 0; k < kinematics::kChainJoints; ++k) {
    starts[0][k] = seed[free[k]];
    middle[k] = 0.5 * (min_rad[k] + max_rad[k]);
  }
  for (const double base : {0.0, kPi / 2, -kPi / 2, kPi}) {
    JointArray start = middle;
    start[0] = base;
    starts.push_back(start);
    start[3] = kPi / 2;
    starts.push_back(start);
  }
  const kinematics::DlsOptions options{.stop_position_m = kSolvedPositionM / 10,
                                       .stop_orientation_rad = kSolvedOrientationRad / 10};
  for (const JointArray& start : starts) {
    const kinematics::DlsResult result = kinematics::solve_dls(goal, start, min_rad, max_rad, frames_of, options);
    if (solved(result.error)) return joints_of(result.q_rad);
  }
  return std::nullopt;
}

Eigen::Isometry3d isometry_of(const Pose& pose) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.translate(Eigen::Vector3d(pose.position_m[0], pose.position_m[1], pose.position_m[2]));
  transform.rotate(Eigen::AngleAxisd(pose.rpy_rad[2], Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pose.rpy_rad[1], Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(pose.rpy_rad[0], Eigen::Vector3d::UnitX()));
  return transform;
}

Pose pose_of(const Eigen::Isometry3d& transform) {
  const Eigen::Matrix3d r = transform.linear();
  const Eigen::Vector3d p = transform.translation();
  Pose pose;
  pose.position_m = {p.x(), p.y(), p.z()};
  // R = Rz(yaw)·Ry(pitch)·Rx(roll): r(2,0) = −sin(pitch).
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  constexpr double kGimbalLock = 1.0 - 1e-9;
  if (std::abs(r(2, 0)) < kGimbalLock) {
    pose.rpy_rad = {std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))};
  } else {  // pitch ±90°: roll and yaw turn about the same axis; all of it as yaw
    pose.rpy_rad = {0.0, pitch, std::atan2(-r(0, 1), r(1, 1))};
  }
  // −180° and 180° are the same turn; the controller writes 180° (atan2 of −0 gives −180°).
  for (double& angle : pose.rpy_rad) {
    if (angle <= -kPi + kSameAngleRad) angle = kPi;
  }
  return pose;
}

}  // namespace robotd::xarm::sim
