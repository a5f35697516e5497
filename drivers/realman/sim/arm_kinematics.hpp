// The arms' geometry from the shared arm models (robotd/kinematics/arm_model.hpp: RealMan's
// modified DH tables): forward kinematics for every model with a usable table, inverse kinematics
// for the 6-joint ones. Poses are the flange in the base frame; Euler angles as the controller
// writes them, fixed axes x-y-z (R = Rz(rz)·Ry(ry)·Rx(rx)).
#pragma once

#include <optional>
#include <string_view>

#include <Eigen/Geometry>

#include "codec/realman_codec.hpp"
#include "robotd/kinematics/arm_model.hpp"

namespace robotd::realman::sim {

/// One row of a modified DH table as get_DH_data reports it.
struct DhRow {
  double a_m = 0;
  double alpha_rad = 0;
  double d_m = 0;
  double offset_rad = 0;
};

class ArmKinematics {
 public:
  /// The geometry `product_version` names ("RM65-B", "RM65-6F", "RM75-B", "RML63-B", "GEN72-B";
  /// a "-6F" model has the longer flange of the six-axis force version). nullopt for a model
  /// without a usable published table (ECO65: its page's columns are inconsistent).
  static std::optional<ArmKinematics> for_product(std::string_view product_version, const ArmModel& model);

  std::size_t dof() const { return geometry_->dof; }
  /// Row `joint` (< dof()) of the table, the flange counted in the last d.
  DhRow row(std::size_t joint) const;
  /// The flange pose for the first dof() entries of `joints_rad`.
  Eigen::Isometry3d flange(const JointValues& joints_rad) const;

  /// Inverse kinematics is offered for 6-joint chains.
  bool solves_poses() const { return dof() == 6; }
  /// Joints within the model's limits that put the flange on `goal` (to 10 µm and 1 mrad),
  /// searched from `seed` first; nullopt when no search reaches it. Needs solves_poses().
  std::optional<JointValues> solve(const Eigen::Isometry3d& goal, const JointValues& seed) const;

 private:
  ArmKinematics(const kinematics::ArmModel& geometry, const ArmModel& model) : geometry_(&geometry), model_(model) {}

  const kinematics::ArmModel* geometry_;
  ArmModel model_;
};

Eigen::Isometry3d isometry_of(const EulerPose& pose);
EulerPose euler_pose_of(const Eigen::Isometry3d& pose);

}  // namespace robotd::realman::sim
