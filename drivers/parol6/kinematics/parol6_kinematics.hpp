// PAROL6 kinematics (spec §11.1) on the shared arm model "parol6" (robotd/kinematics/
// arm_model.hpp: the commander's standard-DH model to the tool, link 6 carrying the 62.8 / 45.25 mm
// tool offset, and its roll/pitch/yaw convention), in the driver's 6-joint types, and a
// damped-least-squares inverse. The moves themselves are planned by robotd/motion, the one home
// of the commander's move rules. Lengths in m, angles in rad.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "codec/parol6_frames.hpp"
#include "robotd/kinematics/arm_model.hpp"

namespace robotd::parol6 {

/// The shared arm model (robotd::kinematics::find_arm_model).
inline constexpr std::string_view kArmModelName = "parol6";

using JointVector = std::array<double, kJoints>;

/// The shared model itself (what robotd/motion plans the ops' moves on).
const kinematics::ArmModel& parol6_model();

/// A tool pose: position in m and orientation in rad, in the convention the commander uses for
/// MovePose(x, y, z, Rx, Ry, Rz) and shows in its GUI: roll_rad, pitch_rad, yaw_rad are its Rx,
/// Ry, Rz, which it turns into a rotation with spatialmath's SE3.RPY([Rx, Ry, Rz], order="xyz"):
///   R = Rx(yaw_rad) · Ry(pitch_rad) · Rz(roll_rad).
/// Despite the argument names, roll (the first angle) turns about z, the tool axis, and yaw (the
/// third) about x; this is not the usual R = Rz(yaw)·Ry(pitch)·Rx(roll). pose_of gives pitch in
/// [−π/2, π/2]; at pitch ±π/2 it sets roll to 0 and puts the whole turn in yaw.
struct Pose {
  double x_m = 0, y_m = 0, z_m = 0;
  double roll_rad = 0, pitch_rad = 0, yaw_rad = 0;
};

Eigen::Isometry3d tool_transform(const JointVector& q_rad) noexcept;
Pose forward_kinematics(const JointVector& q_rad) noexcept;
Eigen::Isometry3d transform_of(const Pose& pose) noexcept;
Pose pose_of(const Eigen::Isometry3d& transform) noexcept;

struct IkResult {
  bool converged = false;  // position error < 0.1 mm and orientation error < 1e-3 rad
  JointVector q_rad{};     // within the limits
  double position_error_m = 0;
  double orientation_error_rad = 0;
};

/// Damped least squares from `seed`, joint limits respected. Not real-time.
IkResult inverse_kinematics(const Pose& target, const JointVector& seed, const JointVector& min_rad,
                            const JointVector& max_rad);

}  // namespace robotd::parol6
