// The arms' geometry from RealMan's modified DH tables (rm_docs, robotParameter pages): forward
// kinematics for every model with a usable table, inverse kinematics for the 6-joint ones
// through robotd::kinematics::solve_dls. Poses are the flange in the base frame; Euler angles as
// the controller writes them, fixed axes x-y-z (R = Rz(rz)·Ry(ry)·Rx(rx)).
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "codec/realman_codec.hpp"

namespace robotd::realman::sim {

/// One row of a modified DH table: frame i from frame i−1 is Rx(α) · Tx(a) · Rz(θ + offset) · Tz(d).
struct DhRow {
  double a_m;
  double alpha_rad;
  double d_m;
  double offset_rad;
};

class ArmKinematics {
 public:
  /// The geometry `product_version` names ("RM65-B", "RM65-6F", "RM75-B", "RML63-B", "GEN72-B";
  /// a "-6F" model has the longer flange of the six-axis force version). nullopt for a model
  /// without a usable published table (ECO65: its page's columns are inconsistent).
  static std::optional<ArmKinematics> for_product(std::string_view product_version, const ArmModel& model);

  std::size_t dof() const { return rows_.size(); }
  const std::vector<DhRow>& rows() const { return rows_; }
  /// The flange pose for the first dof() entries of `joints_rad`.
  Eigen::Isometry3d flange(const JointValues& joints_rad) const;

  /// Inverse kinematics exists for 6-joint chains (the shared solver's size).
  bool solves_poses() const { return rows_.size() == 6; }
  /// Joints within the model's limits that put the flange on `goal` (to 10 µm and 1 mrad),
  /// searched from `seed` first; nullopt when no search reaches it. Needs solves_poses().
  std::optional<JointValues> solve(const Eigen::Isometry3d& goal, const JointValues& seed) const;

 private:
  ArmKinematics(std::vector<DhRow> rows, const ArmModel& model) : rows_(std::move(rows)), model_(model) {}

  std::vector<DhRow> rows_;
  ArmModel model_;
};

Eigen::Isometry3d isometry_of(const EulerPose& pose);
EulerPose euler_pose_of(const Eigen::Isometry3d& pose);

}  // namespace robotd::realman::sim
