#include "arm_kinematics.hpp"

#include <cmath>
#include <numbers>

#include "robotd/kinematics/serial_chain.hpp"

namespace robotd::realman::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMm = 1e-3;
constexpr double kSolvedPositionM = 1e-5;
constexpr double kSolvedOrientationRad = 1e-3;

DhRow row(double a_mm, double alpha_deg, double d_mm, double offset_deg) {
  return DhRow{.a_m = a_mm * kMm, .alpha_rad = alpha_deg * kDeg, .d_m = d_mm * kMm, .offset_rad = offset_deg * kDeg};
}

/// The published tables (mm, degrees); the last d is the flange length of the standard ("-B")
/// version, replaced by `force_flange_mm` on a six-axis force ("-6F") version.
struct PublishedTable {
  std::string_view model;
  std::vector<DhRow> rows;
  double force_flange_mm;
};

std::vector<PublishedTable> published_tables() {
  return {
      {"RM65",
       {row(0, 0, 240.5, 0), row(0, 90, 0, 90), row(256, 0, 0, 90), row(0, 90, 210, 0), row(0, -90, 0, 0),
        row(0, 90, 144, 0)},
       172.5},
      {"RM75",
       {row(0, 0, 240.5, 0), row(0, -90, 0, 0), row(0, 90, 256, 0), row(0, -90, 0, 0), row(0, 90, 210, 0),
        row(0, -90, 0, 0), row(0, 90, 144, 0)},
       172.5},
      {"RML63",
       {row(0, 0, 172, 0), row(-86, -90, 0, -90), row(380, 0, 0, 90), row(69, 90, 405, 0), row(0, -90, 0, 180),
        row(0, -90, 115, 180)},
       143.5},
      {"GEN72",
       {row(0, 0, 218, 0), row(0, -90, 0, 0), row(0, 90, 280, 0), row(40, 90, 0, 0), row(-19, -90, 252.5, 0),
        row(0, 90, 0, 90), row(67, 90, 90.5, 0)},
       90.5},
  };
}

Eigen::Isometry3d link(const DhRow& dh, double q_rad) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.rotate(Eigen::AngleAxisd(dh.alpha_rad, Eigen::Vector3d::UnitX()));
  transform.translate(Eigen::Vector3d(dh.a_m, 0, 0));
  transform.rotate(Eigen::AngleAxisd(q_rad + dh.offset_rad, Eigen::Vector3d::UnitZ()));
  transform.translate(Eigen::Vector3d(0, 0, dh.d_m));
  return transform;
}

bool solved(const kinematics::Twist& error) {
  return error.head<3>().norm() < kSolvedPositionM && error.tail<3>().norm() < kSolvedOrientationRad;
}

}  // namespace

std::optional<ArmKinematics> ArmKinematics::for_product(std::string_view product_version, const ArmModel& model) {
  for (PublishedTable& table : published_tables()) {
    if (table.model != model.name) continue;
    if (product_version.find("-6F") != std::string_view::npos) table.rows.back().d_m = table.force_flange_mm * kMm;
    return ArmKinematics(std::move(table.rows), model);
  }
  return std::nullopt;
}

Eigen::Isometry3d ArmKinematics::flange(const JointValues& joints_rad) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < rows_.size(); ++i) pose = pose * link(rows_[i], joints_rad[i]);
  return pose;
}

std::optional<JointValues> ArmKinematics::solve(const Eigen::Isometry3d& goal, const JointValues& seed) const {
  using kinematics::JointArray;
  JointArray min_rad{};
  JointArray max_rad{};
  for (std::size_t i = 0; i < kinematics::kChainJoints; ++i) {
    min_rad[i] = model_.min_rad[i];
    max_rad[i] = model_.max_rad[i];
  }
  const auto frames_of = [this](const JointArray& q) {
    kinematics::ChainFrames frames;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    for (std::size_t i = 0; i < kinematics::kChainJoints; ++i) {
      pose = pose * link(rows_[i], q[i]);
      frames[i] = pose;  // joint i turns about this frame's z axis, through its origin
    }
    frames[kinematics::kChainJoints] = pose;  // the flange: the last frame carries its length
    return frames;
  };
  const kinematics::DlsOptions options{.stop_position_m = kSolvedPositionM / 10,
                                       .stop_orientation_rad = kSolvedOrientationRad / 10};
  // From the seed first (the nearest solution, so paths stay continuous); then from a few fixed
  // postures, for targets the seed's branch cannot reach.
  std::vector<JointArray> seeds(1);
  for (std::size_t i = 0; i < kinematics::kChainJoints; ++i) seeds[0][i] = seed[i];
  seeds.push_back(JointArray{0, 0.5, 1.0, 0, 1.0, 0});
  seeds.push_back(JointArray{0, -0.5, -1.0, 0, -1.0, 0});
  seeds.push_back(JointArray{1.5, 0.5, 1.0, 1.5, -1.0, 0});
  seeds.push_back(JointArray{-1.5, -0.5, -1.0, -1.5, 1.0, 0});
  for (const JointArray& start : seeds) {
    const kinematics::DlsResult result = kinematics::solve_dls(goal, start, min_rad, max_rad, frames_of, options);
    if (!solved(result.error)) continue;
    JointValues joints{};
    for (std::size_t i = 0; i < kinematics::kChainJoints; ++i) joints[i] = result.q_rad[i];
    return joints;
  }
  return std::nullopt;
}

Eigen::Isometry3d isometry_of(const EulerPose& pose) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.translate(Eigen::Vector3d(pose.position_m[0], pose.position_m[1], pose.position_m[2]));
  transform.rotate(Eigen::AngleAxisd(pose.euler_rad[2], Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pose.euler_rad[1], Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(pose.euler_rad[0], Eigen::Vector3d::UnitX()));
  return transform;
}

EulerPose euler_pose_of(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d p = pose.translation();
  EulerPose out;
  out.position_m = {p.x(), p.y(), p.z()};
  const double ry = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  if (std::abs(r(2, 0)) < 1.0 - 1e-9) {
    out.euler_rad = {std::atan2(r(2, 1), r(2, 2)), ry, std::atan2(r(1, 0), r(0, 0))};
  } else {  // gimbal lock: rx and rz turn about the same axis; put it all in rz
    out.euler_rad = {0.0, ry, std::atan2(-r(0, 1), r(1, 1))};
  }
  return out;
}

}  // namespace robotd::realman::sim
