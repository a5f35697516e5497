// The arms' geometry from the shared arm models (robotd/kinematics/arm_model.hpp: UFACTORY's
// standard D-H tables): forward kinematics for every model, inverse kinematics for the 6- and
// 7-joint ones (on a 7-joint arm joint 3 is held where it is and the other six are solved).
// Poses are the TCP (the flange and the TCP offset) in the base frame; roll, pitch, yaw fixed
// axes X-Y-Z.
#pragma once

#include <cstddef>
#include <optional>

#include <Eigen/Geometry>

#include "codec/xarm_codec.hpp"
#include "robotd/kinematics/arm_model.hpp"

namespace robotd::xarm::sim {

class ArmKinematics {
 public:
  /// The geometry of the model's family (ArmModel::kinematic_model).
  static ArmKinematics for_model(const ArmModel& model);

  std::size_t dof() const { return geometry_->dof; }
  /// The flange for the first dof() entries of `joints_rad`.
  Eigen::Isometry3d flange(const JointValues& joints_rad) const;
  /// The flange carrying `tcp_offset`.
  Eigen::Isometry3d tcp(const JointValues& joints_rad, const Eigen::Isometry3d& tcp_offset) const;

  /// Whether solve() works: 6 or 7 joints (a 5-joint arm cannot reach an arbitrary pose).
  bool solves_poses() const { return dof() >= 6; }
  /// Joints within the model's limits that put the TCP on `goal` (to 10 µm and 1 mrad), searched
  /// from `seed` first; a 7-joint arm keeps joint 3 at the seed's value. nullopt when no search
  /// reaches it.
  std::optional<JointValues> solve(const Eigen::Isometry3d& goal, const Eigen::Isometry3d& tcp_offset,
                                   const JointValues& seed) const;

 private:
  ArmKinematics(const kinematics::ArmModel& geometry, const ArmModel& model) : geometry_(&geometry), model_(model) {}

  const kinematics::ArmModel* geometry_;
  ArmModel model_;
};

/// A pose as a transform (R = Rz(yaw)·Ry(pitch)·Rx(roll)) and back.
Eigen::Isometry3d isometry_of(const Pose& pose);
Pose pose_of(const Eigen::Isometry3d& transform);

}  // namespace robotd::xarm::sim
